#!/usr/bin/env bash
# The README's second command: set up, build, and run every test (CTest + GoogleTest).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh -DNEOPIPE_BUILD_TESTING=ON  # on again after scripts/demo.sh turned it off
ctest --test-dir build --output-on-failure --no-tests=error -j "$(nproc)"
