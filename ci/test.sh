#!/usr/bin/env bash
# One command on a fresh machine: installs what is missing, then runs the stages below in order,
# each under a banner. The first stage that fails stops the run, and the last line names it.
#   release build      ci/build.sh into build/ (RelWithDebInfo): the installed libraries and the
#                      tests labelled `release` (heap and RSS bounds over long frame loops and
#                      create/destroy cycles, which need the uninstrumented allocator; the
#                      walkthrough), then those tests
#   install + consumer ci/package.sh: cmake --install into build-install/, the consumer project
#                      tests/package configured against it (find_package(sao CONFIG)), built, run
#   sanitizers         ci/sanitize.sh: AddressSanitizer + UndefinedBehaviorSanitizer build of
#                      everything in build-asan/, every ctest test (leak checking on) but those
#                      labelled release_only (run uninstrumented in the release stage)
#   fuzz               ci/fuzz.sh: the libFuzzer targets (clang) in build-fuzz/, a fixed number of
#                      inputs from a fixed seed each (deterministic: the verdict depends on the
#                      commit alone); ci/fuzz.sh --explore SECONDS is the time-based run
# Every test runs once under the sanitizers rather than twice (plain and sanitized), which kept CI
# under 30 minutes on 2 cores; `ci/build.sh && ctest --test-dir build` is the whole suite uninstrumented.
# SAO_CI_STAGES picks stages by key (build package sanitizers fuzz), e.g. SAO_CI_STAGES="build fuzz".
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

stages="${SAO_CI_STAGES:-build package sanitizers fuzz}"
current=""
summary=()
t0=$SECONDS
on_exit() {
  local rc=$?
  if [ $rc -ne 0 ] && [ -n "$current" ]; then
    echo
    echo "==== CI FAILED in stage '$current' (exit $rc) after $((SECONDS - t0)) s"
  fi
}
trap on_exit EXIT

run_stage() {
  local key=$1 name=$2
  shift 2
  case " $stages " in *" $key "*) ;; *) return 0 ;; esac
  current="$name"
  echo
  echo "==== stage: $name"
  local start=$SECONDS
  "$@"
  summary+=("$(printf '%-20s %5d s' "$name" $((SECONDS - start)))")
  echo "==== stage '$name' passed in $((SECONDS - start)) s"
  current=""
}

release_build_and_test() {
  bash ci/build.sh --target sao_installed_libraries sao_release_tests
  ctest --test-dir build --output-on-failure --timeout 900 -j "$(nproc)" -L release
}

current="setup"
bash ci/setup.sh
current=""
run_stage build "release build" release_build_and_test
run_stage package "install + consumer" bash ci/package.sh build
run_stage sanitizers "sanitizers" bash ci/sanitize.sh -LE release_only  # those run in the release stage
run_stage fuzz "fuzz" bash ci/fuzz.sh

echo
echo "==== CI passed in $((SECONDS - t0)) s"
printf '  %s\n' "${summary[@]}"
