#!/usr/bin/env bash
# Installs the Debian packages cushion needs (as root), only those missing.
set -euo pipefail
packages=(cmake g++ make libeigen3-dev libsuitesparse-dev libtet1.5-dev paraview-dev python3-paraview libgtest-dev
          libcli11-dev nlohmann-json3-dev libceres-dev gnuplot-nox python3
          libopenblas0-pthread libpetsc-real-dev libmetis-dev)
# paraview-dev: the VTK that Debian's ParaView 5.11 ships (with its CMake config), so the build and ParaView's pvpython
# (python3-paraview, used by the output check) live on one machine; Debian 12's libvtk9-dev cannot, because its
# python3-vtk9 conflicts with python3-paraview. apt removes libvtk9-dev if it is installed.
# OpenBLAS for CHOLMOD/UMFPACK (ATLAS, pulled in otherwise, is much slower)
# PETSc 3.18 (with OpenMPI, MUMPS, hypre) for "linear_solver": "petsc": Krylov + algebraic multigrid for models
# past what one sparse factorization handles (issue 14); the build skips that solver when it is absent.
# METIS partitions the mesh of a distributed run (mpirun -np N cushion run ...).
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "deps: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
echo "deps: all packages present"
