#!/usr/bin/env bash
# One command on a fresh machine: install, build, run every test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash ci/setup.sh
bash ci/build.sh
ctest --test-dir build --output-on-failure --timeout 900 -j "$(nproc)"
