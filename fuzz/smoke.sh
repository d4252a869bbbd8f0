#!/usr/bin/env bash
# Fuzz smoke run for CI: every target for a few seconds to a minute (about 4 minutes in all),
# memory-capped and time-capped per input. Needs a nightly toolchain and cargo-fuzz; without
# them it prints one visible "fuzz smoke run skipped: ..." line and succeeds. A crash, OOM or
# hang fails (the input is left in fuzz/artifacts/<target>/).
# FUZZ_SMOKE_SECONDS scales the per-target time (default 30).
set -euo pipefail
cd "$(dirname "$0")"
if ! cargo +nightly --version >/dev/null 2>&1; then
  echo "fuzz smoke run skipped: no nightly toolchain (rustup toolchain install nightly)"
  exit 0
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "fuzz smoke run skipped: cargo-fuzz not installed (cargo install cargo-fuzz)"
  exit 0
fi
secs=${FUZZ_SMOKE_SECONDS:-30}
./seed-corpus.sh >/dev/null
# No sanitizer: the code under test is safe Rust; libFuzzer still catches panics (overflow
# checks are on), aborts, out-of-memory (-rss_limit_mb, -malloc_limit_mb) and hangs (-timeout).
cargo +nightly fuzz build -s none
run() { # target seconds
  local log="artifacts/smoke-$1.log"
  mkdir -p artifacts
  if ! cargo +nightly fuzz run -s none "$1" "corpus/$1" -- \
      -max_total_time="$2" -rss_limit_mb=500 -malloc_limit_mb=500 -timeout=10 \
      -print_final_stats=1 >"$log" 2>&1; then
    tail -n 40 "$log"
    echo "fuzz smoke: $1 FAILED (log $log, input in fuzz/artifacts/$1/)"
    exit 1
  fi
  echo "fuzz smoke: $1 ok: $(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}') runs in $2 s, peak RSS $(grep -E '^stat::peak_rss_mb' "$log" | awk '{print $2}') MB"
}
run reader_raw "$secs"
run reader_struct "$secs"
run import_inp "$secs"
run import_bdf "$secs"
run import_msh "$secs"
run import_mtx "$((secs / 2))"
run options "$((secs / 3))"
echo "fuzz smoke run: no crash, OOM or hang"
