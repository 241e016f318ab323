#!/bin/sh
# ci/gpu-bench.sh's argument errors, without building or running anything: a missing bundle, a
# missing FILE and an unknown option each exit 2 with a message naming the problem.
# usage: gpu_bench_usage.sh REPO_ROOT
set -u
script=$1/ci/gpu-bench.sh
die() { echo "gpu-bench usage: $*" >&2; exit 1; }
expect() {
  want=$1; shift
  out=$(bash "$script" "$@" 2>&1); rc=$?
  [ "$rc" -eq 2 ] || die "ci/gpu-bench.sh $*: exit $rc, expected 2 ($out)"
  echo "$out" | grep -qF -e "$want" || die "ci/gpu-bench.sh $*: expected '$want', got: $out"
}
expect "gpu-bench: no bundle '/nonexistent/bundle.tar.xz'" --from-bundle /nonexistent/bundle.tar.xz
expect "usage: ci/gpu-bench.sh --bundle FILE" --bundle
expect "usage: ci/gpu-bench.sh --from-bundle FILE [OUT]" --from-bundle
expect "usage: ci/gpu-bench.sh [OUT] | --bundle FILE | --from-bundle FILE [OUT]" --bogus
echo "gpu-bench usage: ok"
