#!/usr/bin/env bash
# Installs the Debian 12 packages FaceHex needs to build, test and run, only those missing.
# `install-deps.sh fuzz` adds what the fuzz build needs (scripts/fuzz.sh): clang with libFuzzer and ASan, and the
# LLVM OpenMP runtime clang links.
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libeigen3-dev libsuitesparse-dev libtet1.5-dev nlohmann-json3-dev
  libblas-dev  # cblas.h; the BLAS linked is the one Debian selects at run time (OpenBLAS, below)
  libopenblas0-pthread  # CHOLMOD's supernodal factorization runs on BLAS; the reference BLAS is several times slower
  libvtk9-dev libvtk9-qt-dev qtbase5-dev libqt5opengl5-dev
  libgdcm-dev  # DICOM series: scanning, any transfer syntax
  libgtest-dev
  zlib1g-dev  # NIfTI headers of .nii.gz files are checked before VTK reads them
  libssl-dev  # SHA-256 of a run's outputs in its report's completion record
  calculix-ccx gmsh  # the FE export tests run the CalculiX solver and Gmsh on exported models
  xvfb xauth libgl1-mesa-dri
  snakemake python3-vtk9  # cohorts: workflow/Snakefile; make cohort-demo warps the bundled CT in Python
  python3-numpy  # the docs' scripts (scripts/regenerate-docs.sh) read and write VTK arrays with it
  slurm-wlm munge  # the cohort test on a single-node Slurm cluster (scripts/local-slurm.sh)
)
if [ "${1:-}" = fuzz ]; then packages+=(clang libclang-rt-14-dev libomp-dev); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "facehex: installing missing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
