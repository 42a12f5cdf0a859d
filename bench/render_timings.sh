# render_timings.sh: sourced by the bench/*.sh timing scripts: prints the device header and defines
# `run NAME ARGS...`, which renders to out/bench/NAME.png with $lucent and prints its timing summary.
mkdir -p out/bench
run() {
  local name=$1; shift
  echo "== $name: $lucent render $*"
  "$lucent" render "$@" -o "out/bench/$name.png" 2>/dev/null | sed -n "2,14p"
}
date -u +"date: %Y-%m-%d %H:%M UTC"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
