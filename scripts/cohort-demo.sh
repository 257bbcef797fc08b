#!/usr/bin/env bash
# `make cohort-demo`: a small cohort meshed by the cohort workflow (workflow/Snakefile, docs/cohorts.md) on this
# machine: the bundled CT, three smooth warps of it (scripts/make_ct_variants.py), and the Visible Human Female head CT
# when ../shared/data/ct/vhfemale-head.mha is there, at a coarse edge length. Writes OUT/manifest.csv, OUT/ID/ per
# patient and the cohort report OUT/cohort.md (.json, .csv, PNG plots).
# Usage: scripts/cohort-demo.sh OUT CORES EDGE_LENGTH   (from the repository root)
set -euo pipefail
out=${1:?usage: $0 OUT CORES EDGE_LENGTH}
cores=${2:?usage: $0 OUT CORES EDGE_LENGTH}
edge=${3:?usage: $0 OUT CORES EDGE_LENGTH}
mkdir -p "$out/inputs"
for v in wide long chin; do
  # Debian's Python, which has VTK (python3-vtk9), whatever python3 comes first on the PATH.
  [ -f "$out/inputs/$v.mha" ] || { /usr/bin/python3 scripts/make_ct_variants.py "$out/inputs" > /dev/null; break; }
done
root=$(pwd)
{
  echo "id,input"
  echo "headsq,$root/resources/ct/headsq/headsq.mhd"
  for v in wide long chin; do echo "headsq-$v,inputs/$v.mha"; done
  vhf=$root/../shared/data/ct/vhfemale-head.mha
  [ -f "$vhf" ] && echo "vhfemale,$(realpath "$vhf")"
} > "$out/manifest.csv.tmp"
# Rewritten only when it changes, so that a second `make cohort-demo` finds nothing to do.
cmp -s "$out/manifest.csv.tmp" "$out/manifest.csv" && rm "$out/manifest.csv.tmp" || mv "$out/manifest.csv.tmp" "$out/manifest.csv"
snakemake --snakefile workflow/Snakefile --cores "$cores" --keep-going \
  --config manifest="$out/manifest.csv" out="$out" edge_length="$edge" threads=1
echo "cohort report: $out/cohort.md"
