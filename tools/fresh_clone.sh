#!/usr/bin/env bash
# Times the README's two commands as a new user meets them: a fresh clone of this repository's HEAD in a new
# folder, each command run as the README gives it (the first two ```sh blocks), its output and wall time
# written to LOG.
#
#   tools/fresh_clone.sh LOG [--purge]
#
# --purge first removes the Debian packages the commands install (not g++, cmake, make and python3, which a
# new Debian 12 machine of this kind has), so the first command installs them again as on a fresh machine.
set -euo pipefail
log=$(realpath -m "${1:?usage: tools/fresh_clone.sh LOG [--purge]}")
repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work=$(mktemp -d /tmp/grainflow-fresh-XXXXXX)
if [ "${2:-}" = "--purge" ]; then
  DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq libeigen3-dev libxsimd-dev xtl-dev libtbb-dev \
    libtomlplusplus-dev nlohmann-json3-dev libpng-dev libcairo2-dev libccd-dev libcli11-dev libbenchmark-dev catch2 libopenmpi-dev \
    openmpi-bin python3-matplotlib python3-numpy >/dev/null
  DEBIAN_FRONTEND=noninteractive apt-get autoremove -y -qq >/dev/null
fi
git clone -q "$repo" "$work/grainflow"
cd "$work/grainflow"
{
  echo "# fresh clone of $(git rev-parse HEAD) ($(git log -1 --format=%cs)) in $work/grainflow"
  echo "# machine: $(nproc) cores, $(free -g | awk '/Mem:/ {print $2}') GiB, $(lscpu | sed -n 's/^Model name: *//p')"
  echo "# purged the project's packages first: $([ "${2:-}" = "--purge" ] && echo yes || echo no)"
} > "$log"
python3 - README.md > "$work/commands" <<'PY'
import re, sys
blocks = re.findall(r"```sh\n(.*?)\n```", open(sys.argv[1]).read(), re.S)
print(blocks[0]); print(blocks[1])
PY
n=0
while IFS= read -r cmd; do
  n=$((n + 1))
  echo "## command $n: $cmd" >> "$log"
  start=$(date +%s)
  set +e
  bash -c "$cmd" >> "$log" 2>&1
  rc=$?
  set -e
  echo "## command $n: exit status $rc, wall time $(( $(date +%s) - start )) s" >> "$log"
done < "$work/commands"
grep '^## command .*wall time' "$log"
echo "the clone and its build are left in $work for inspection; remove it with: rm -rf $work"
