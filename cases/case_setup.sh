# Sourced by every case's run.sh, first thing after `set -euo pipefail`:
#   source "$(dirname "$0")/../case_setup.sh" "${1:-flexmbs}"
# Sets `here` (the case's folder), `flexmbs` (the binary; a path, not a name looked up on PATH,
# made absolute) and `out` (FLEXMBS_OUT, else here/out; created), then changes into `here`.
here="$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)"
flexmbs="$1"
case "$flexmbs" in */*) flexmbs="$(cd "$(dirname "$flexmbs")" && pwd)/$(basename "$flexmbs")" ;; esac
out="${FLEXMBS_OUT:-$here/out}"
mkdir -p "$out"
cd "$here"
