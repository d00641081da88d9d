#!/usr/bin/env bash
# Preprocesses the steel cantilever: mesh and FE model report (text and JSON).
# Usage: run.sh [path/to/flexmbs]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
flexmbs="${1:-flexmbs}"
out="${FLEXMBS_OUT:-$here/out}"
mkdir -p "$out"
"$flexmbs" mesh "$here/beam.yaml"
"$flexmbs" mesh "$here/beam.yaml" --json > "$out/beam.mesh.json"
echo "wrote $out/beam.mesh.json"
