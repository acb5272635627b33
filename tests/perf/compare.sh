#!/usr/bin/env bash
# The whole-process figures of docs/performance.md, in one run: each
# workload run by this checkout's release `linc` and by a previous
# release's (built once from BASE in a worktree under target/perf), beside
# a native Rust equivalent built with `rustc -O` where one exists. Each
# command runs ROUNDS times, the builds taking turns; the best wall time
# and its peak memory are kept (a busy machine only ever makes a run
# slower).
#
#   tests/perf/compare.sh BASE-COMMIT [ROUNDS]      # prints a Markdown table
set -euo pipefail
cd "$(dirname "$0")/../.."
base=$(git rev-parse --short "${1:?usage: tests/perf/compare.sh BASE-COMMIT [ROUNDS]}")
rounds=${2:-5}
out=target/perf
mkdir -p "$out"

cargo build -q --release -p linc
cp target/release/linc "$out/linc-head"
if [ "$base" = "$(git rev-parse --short HEAD)" ] && git diff --quiet HEAD -- . ':!tests/perf' ':!docs'; then
  cp "$out/linc-head" "$out/linc-$base"   # this checkout is the base: one build
elif [ ! -x "$out/linc-$base" ]; then
  rm -rf "$out/base-src"
  git worktree add -q -f --detach "$out/base-src" "$base"
  (cd "$out/base-src" && CARGO_TARGET_DIR="$PWD/../base-target" cargo build -q --release -p linc)
  cp "$out/base-target/release/linc" "$out/linc-$base"
  git worktree remove --force "$out/base-src"
fi
for k in int poly shift strings; do
  rustc -O -o "$out/native-$k" "tests/perf/native/$k.rs"
done
# The 5 MB of dense realistic actions the check benchmark generates.
(cd compiler && cargo bench -q --bench check -- --test "check actions" >/dev/null)
actions=target/check-actions-5M.st

# one CMD...: one run's wall time (s, to the microsecond: time(1)'s own
# is to the hundredth) and peak memory (KB).
one() {
  local s t
  s=$EPOCHREALTIME
  /usr/bin/time -f "%M" -o "$out/time" "$@" >/dev/null 2>&1 || { echo "failed: $*" >&2; exit 1; }
  t=$(awk "BEGIN{ printf \"%.4f\", $EPOCHREALTIME - $s }")
  echo "$t $(tail -1 "$out/time")"
}

# race WHO...: the best wall time of each of the builds WHO (base, head or
# native, the command being "${cmd[@]}" after the build's binary, or
# native-$k alone), and that run's peak memory, as "t m" pairs in order.
# The builds take turns, one run each per round: this machine's speed
# drifts by a third over minutes, and seven runs of one build followed by
# seven of the next measured the drift as much as the builds.
race() {
  local -a bt bm
  local i t m
  for _ in $(seq "$rounds"); do
    i=0
    for who in "$@"; do
      case $who in
        native) read -r t m < <(one "$out/native-$k") ;;
        *) read -r t m < <(one "$out/linc-$who" "${cmd[@]}") ;;
      esac
      if [ -z "${bt[$i]:-}" ] || awk "BEGIN{exit !($t < ${bt[$i]})}"; then bt[$i]=$t; bm[$i]=$m; fi
      i=$((i + 1))
    done
  done
  for i in "${!bt[@]}"; do printf '%s %s ' "${bt[$i]}" "${bm[$i]}"; done
  echo
}

ratio() { awk "BEGIN{ if ($2 > 0) printf \"%.2f×\", $1 / $2; else print \"-\" }"; }

db=examples/guide/plant.db.json
echo "| workload | command | $base | head | native | head ÷ native |"
echo "|---|---|---|---|---|---|"
for k in int poly shift strings; do
  cycles=1; [ "$k" = strings ] && cycles=50
  cmd=(run "tests/perf/kernels/$k.stx" --db "$db" --cycles "$cycles" --watchdog 4000000000 --tier compiled)
  read -r b _ h _ n _ < <(race "$base" head native)
  echo "| kernel \`$k\` | \`linc ${cmd[*]}\` | $b s | $h s | $n s | $(ratio "$h" "$n") |"
done
mbps() { awk "BEGIN{ printf \"%.1f MB/s\", $1 / 1e6 / $2 }"; }
mem() { awk "BEGIN{ printf \"%.1f×\", $2 * 1024 / $1 }"; }
# Both sizes the benchmark writes: the larger is four times the smaller,
# and issue 30 allows it at most 4.4 times the time.
for file in target/check-actions-1.25M.st "$actions"; do
  size=$(stat -c %s "$file")
  cmd=(check "$file" --db "$db")
  read -r b bm h hm < <(race "$base" head)
  echo "| \`linc check\` of $((size / 1000)) kB of actions | \`linc ${cmd[*]}\` | $b s, $(mbps "$size" "$b"), peak $(mem "$size" "$bm") the source | $h s, $(mbps "$size" "$h"), peak $(mem "$size" "$hm") the source | | |"
done
for plant in strategy sequences ladder fst roc; do
  cmd=(run "examples/$plant/plant.json" --for 24h)
  read -r b _ h _ < <(race "$base" head)
  echo "| a day of \`examples/$plant\` (plant time) | \`linc ${cmd[*]}\` | $b s | $h s | | |"
done
