#!/usr/bin/env bash
# Runs facesort's matplotlib tests against each listed matplotlib release, each in a fresh
# virtual environment with the wheel built once. Usage (from the repository's root):
#   bash python/scripts/matplotlib_versions.sh [VERSION ...]
# Default: the oldest and newest patch release of every minor version from 3.8 on.
set -euo pipefail
cd "$(dirname "$0")/../.."
versions=("$@")
[ "${#versions[@]}" -gt 0 ] || versions=(3.8.0 3.8.4 3.9.0 3.9.4 3.10.0 3.10.9 3.11.0 3.11.2)
work="$(mktemp -d)"
python3 -m pip wheel --quiet --no-deps --wheel-dir "$work/wheels" ./python
for v in "${versions[@]}"; do
  python3 -m venv "$work/$v"
  numpy="numpy"
  # matplotlib 3.8 was built against numpy 1.
  case "$v" in 3.8.*) numpy="numpy<2" ;; esac
  "$work/$v/bin/pip" install --quiet "$work"/wheels/facesort-*.whl "matplotlib==$v" "$numpy" pytest hypothesis
  if (cd python && "$work/$v/bin/python" -m pytest -q tests/test_mpl_exact.py -p no:cacheprovider >"$work/$v.log" 2>&1); then
    echo "matplotlib $v: $(tail -1 "$work/$v.log")"
  else
    echo "matplotlib $v: FAILED: $(tail -1 "$work/$v.log")"; tail -30 "$work/$v.log"
  fi
done
rm -rf "$work"
