#!/usr/bin/env bash
# First README command: installs missing Debian packages (as root), builds cushion (Release) in
# ./build, and runs the main job on the shipped default data (tools/demo.sh), ending with where the
# outputs are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target cushion
bash tools/demo.sh
