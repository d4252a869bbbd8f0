#!/usr/bin/env bash
# Fills fuzz/corpus/<target>/ with seeds: the committed fuzz/seeds/ and the repository's
# fixtures (every .flexbody for the reader; decks and meshes under 64 KiB for the importers).
# Idempotent; the fuzzer adds what it finds to the same folders.
set -euo pipefail
cd "$(dirname "$0")"
fx=../fixtures
mk() { mkdir -p "corpus/$1"; }
for t in reader_raw reader_struct import_inp import_bdf import_msh import_mtx options; do mk "$t"; done
find "$fx" -name '*.flexbody' -exec cp {} corpus/reader_raw/ \;
# reader_struct: [selector, mode] + bytes; empty replacement bytes in mode 1 = the golden file
# unchanged, one seed per (base file, entry).
for sel in $(seq 0 63); do
  printf "$(printf '\\%03o\\001' "$sel")" > "corpus/reader_struct/sel_$sel"
done
small() { find "$fx" "$@" -size -64k -type f; }
cp seeds/import_inp/* corpus/import_inp/
small -name '*.inp' -exec cp {} corpus/import_inp/ \;
cp seeds/import_bdf/* corpus/import_bdf/
small \( -name '*.bdf' -o -name '*.blk' -o -name '*.dat' \) -exec cp {} corpus/import_bdf/ \;
small -name '*.msh' -exec cp {} corpus/import_msh/ \;
cp seeds/import_mtx/* corpus/import_mtx/
cp seeds/options/* corpus/options/
for t in corpus/*; do echo "$t: $(ls "$t" | wc -l) seeds"; done
