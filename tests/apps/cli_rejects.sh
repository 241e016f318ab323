#!/bin/sh
# The command line of sao-bench, sao-viewer, sao-gl-timing and sao-vk-timing (sao/cli, CLI11)
# refuses bad options before any work: for each row of the tool's table below, exit status 2,
# nothing on stdout, exactly one line on stderr that starts with "TOOL: " and holds the row's
# text. --help: exit 0, "usage: TOOL [options]" first on stdout, nothing on stderr.
# (sao-render has its own table: render_rejects.sh.)
#
#   cli_rejects.sh TOOL WORK_DIR
set -u
tool=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")  # absolute: the rows run in WORK_DIR
name=$(basename "$tool")
mkdir -p "$2" && cd "$2" || exit 1

fail=0
check() {  # SUBSTRING ARGS...
  want=$1
  shift
  # A row accepted by mistake would start the real work: the timeout bounds it.
  timeout 60 "$tool" "$@" >stdout.txt 2>stderr.txt
  rc=$?
  err=$(cat stderr.txt)
  echo "$* -> $rc: $err"
  problem=""
  [ "$rc" -eq 2 ] || problem="exit status $rc, want 2"
  [ -s stdout.txt ] && problem="$problem; wrote to stdout"
  [ "$(wc -l < stderr.txt)" -eq 1 ] || problem="$problem; stderr is not one line"
  case $err in "$name: "*) ;; *) problem="$problem; stderr does not start with '$name: '" ;; esac
  printf '%s\n' "$err" | grep -qF -e "$want" || problem="$problem; stderr lacks '$want'"
  [ -z "$problem" ] || { echo "  FAIL:$problem"; fail=1; }
}

# What every tool's parser does alike.
check "unknown option '--nosuch'" --nosuch
check "unexpected argument 'stray'" stray
check "--size needs a value" --size
check "--size expects WxH, got '64'" --size 64
check "--size width expects a whole number in [1, 16384], got '20000'" --size 20000x10
check "--size height expects a whole number in [1, 16384], got '0'" --size 64x0

case $name in
  sao-bench)
    check "--runs expects a whole number in [1, 1000], got '0'" --runs 0
    check "--rays expects a whole number in [1, 65536], got '0'" --rays 0
    check "--sections: unknown section 'nope'" --sections presets,nope
    check "--depth-source expects raster or raytrace, got 'auto'" --depth-source auto
    check "--units expects m, cm, mm, in, ft or auto, got 'km'" --units km
    check "--out needs a value, got an empty string" --out ""
    check "--quick takes no value (or true or false), got 'x'" --quick=x
    # --quick sets --size, --runs and --rays: given with it they were silently replaced.
    check "--quick and --size cannot be combined: --quick sets --size" --quick --size 64x36
    check "--quick and --runs cannot be combined: --quick sets --runs" --quick --runs 2
    check "--quick and --rays cannot be combined: --quick sets --rays" --rays 8 --quick
    # A typo in --backends: was exit 1 at run time ('metal'), or skipped with a warning ('gl,metal').
    check "--backends: unknown backend 'metal' (expected gl, vulkan, cpu, cpu-double or auto)" --backends metal
    check "--backends: unknown backend 'metal' (expected gl, vulkan, cpu, cpu-double or auto)" --backends gl,metal
    check "--backends: an empty name in 'gl,'" --backends gl,
    # --frames-averaged: the presets section's errors of averaged frames, never silently ignored.
    check "--frames-averaged expects a whole number in [1, 1024], got '0'" --frames-averaged 0
    check "--frames-averaged sets the presets section's errors: add --sections presets" --frames-averaged 4
    check "--frames-averaged sets the presets section's errors: add --sections presets (and no --tune or --time-only)" --sections presets --time-only --frames-averaged 4
    check "--frames-averaged averages independent frames: the setting temporal blends frames itself" --sections presets --set temporal=true --frames-averaged 4
    ;;
  sao-viewer)
    check "--z-level expects a whole number in [0, 15], got '16'" --z-level 16
    check "--reference-rays expects a whole number in [1, 65536], got '0'" --reference-rays 0
    check "--frames expects a whole number in [0, 1000000000], got '-1'" --frames -1
    check "--view expects a whole number in [0, 1000], got 'one'" --view one
    check "--screenshot needs --frames N" --screenshot x.png
    check "--scene needs a value, got an empty string" --scene ""
    check "--screenshot 'x.txt': sao-viewer writes a PNG file there, so its name must end in .png" --frames 1 --screenshot x.txt
    check "--overwrite has no effect without --screenshot" --frames 1 --overwrite
    check "unknown preset 'nope'" --preset nope
    check "setting 'radius' = 1000 is outside its range" --preset high --set radius=1000
    # Options that would have no effect: a backend's flag on the other backend, a --set setting
    # the final settings make inert (gen::kInertRules; a preset's own values never count).
    check "--validation has no effect with --backend gl: it adds the Vulkan validation layer" --validation
    check "--validation has no effect with --backend gl" --backend vulkan --backend gl --validation
    check "--standard-depth has no effect with --backend vulkan: it turns off the GL viewer's glClipControl" --backend vulkan --standard-depth
    check "--set fade_start has no effect while fade_end = 0 (no distance fade" --set fade_start=2
    check "--set temporal_hysteresis has no effect while temporal = false" --set temporal_hysteresis=0.5
    check "--set blur_stride has no effect while blur_radius = 0 (no bilateral blur" --preset low --set blur_radius=0 --set blur_stride=2
    check "--set half_intermediates has no effect while blur_radius = 0, resolution_divisor = 1 and temporal = false" --preset reference --set blur_radius=0 --set half_intermediates=false
    ;;
  sao-gl-timing)
    # Were std::atoi: 'x' ran 5 runs, -1 a guard band of 4294967295, 3 runs silently 5.
    check "--runs expects a whole number in [5, 1000], got 'x'" --runs x
    check "--runs expects a whole number in [5, 1000], got '3'" --runs 3
    check "--guard expects a whole number in [0, 4096], got '-1'" --guard -1
    check "unknown preset 'nope'" --preset nope
    check "unknown option '--format'" --format D16
    ;;
  sao-vk-timing)
    # Were std::atoi and an unchecked format: 'x' ran 5 runs, 'd17' measured D32F.
    check "--runs expects a whole number in [5, 1000], got 'x'" --runs x
    check "--format expects D16, D24 or D32F, got 'd17'" --format d17
    check "unknown preset 'nope'" --preset nope
    check "unknown option '--guard'" --guard 2
    ;;
  *) echo "no table for $name"; exit 1 ;;
esac

"$tool" --help >stdout.txt 2>stderr.txt
rc=$?
if [ "$rc" -ne 0 ] || [ -s stderr.txt ] || [ "$(head -n 1 stdout.txt)" != "usage: $name [options]" ] ||
   ! grep -qF -e "--size WxH" stdout.txt; then
  echo "--help -> $rc: want exit 0, usage on stdout, empty stderr"; fail=1
fi
exit $fail
