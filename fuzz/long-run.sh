#!/usr/bin/env bash
# Long fuzz runs for the acceptance of issue 20 (the figures in fuzz/README.md): each target in
# turn, at the lowest CPU priority, for a fixed number of executions, memory-capped (2 GB RSS)
# and time-capped (10 s per input). Prints one table row per target; a crash, OOM or hang
# stops that target (libFuzzer's exit code is shown, the input is in fuzz/artifacts/<target>/).
# Usage: fuzz/long-run.sh [target[:runs[:extra libFuzzer flags]] ...]
# Default: the counts of the acceptance (10^7 reader, 10^6 per importer and the options).
# Needs nightly and cargo-fuzz, like fuzz/smoke.sh.
set -uo pipefail
cd "$(dirname "$0")"
if [ $# -eq 0 ]; then
  set -- options:1000000 import_mtx:1000000 import_bdf:1000000 import_msh:1000000 \
    import_inp:1000000:-max_len=65536 reader_raw:10000000 reader_struct:1000000
fi
./seed-corpus.sh >/dev/null
mkdir -p artifacts
if ! cargo +nightly fuzz build -s none >artifacts/long-build.log 2>&1; then
  tail -n 30 artifacts/long-build.log
  exit 2
fi
bin=target/$(rustc +nightly -vV | sed -n "s/^host: //p")/release
echo "| target | executions | exec/s | wall | peak RSS | exit |"
echo "|---|---:|---:|---:|---:|---|"
for spec in "$@"; do
  IFS=: read -r t runs extra <<<"$spec"
  mkdir -p "artifacts/$t"
  log="artifacts/long-$t.log"
  s=$(date +%s)
  # shellcheck disable=SC2086  # extra holds libFuzzer flags, split on purpose
  nice -n 19 "$bin/$t" "corpus/$t" -artifact_prefix="artifacts/$t/" -rss_limit_mb=2048 \
    -timeout=10 -runs="${runs:-1000000}" ${extra:-} -print_final_stats=1 >"$log" 2>&1
  rc=$?
  stat() { grep -E "^stat::$1" "$log" | awk '{print $2}'; }
  echo "| \`$t\` | $(stat number_of_executed_units) | $(stat average_exec_per_sec) | $(($(date +%s) - s)) s | $(stat peak_rss_mb) MB | $rc |"
done
