#!/usr/bin/env bash
# The README's first command: install Debian's packages, build, and run the
# main job on its embedded default.  Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
# The tests read VTK files through Python's vtkmodules.  Debian 12's
# python3-paraview ships its own vtkmodules (the same readers) and conflicts
# with python3-vtk9: on a machine with ParaView's Python, that one serves and
# python3-vtk9 is not asked for (docs/install.md).
VTK_PY=python3-vtk9
if dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  VTK_PY=""
  echo "install.sh: python3-paraview is installed; its vtkmodules serve the tests (no python3-vtk9)"
fi
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  build-essential cmake pkg-config \
  mesa-vulkan-drivers libvulkan-dev vulkan-tools vulkan-validationlayers glslang-tools glslang-dev \
  libtet1.5-dev libopenexr-dev openexr libcjson-dev libpng-dev libcairo2-dev fonts-dejavu-core zlib1g-dev libmuparser-dev \
  $VTK_PY python3-meshio python3-numpy python3-scipy openimageio-tools python3-openimageio man-db zsh assimp-utils >/dev/null
/usr/bin/python3 -c "import vtkmodules.vtkIOXML, vtkmodules.vtkIOPLY, vtkmodules.vtkIOGeometry" ||
  echo "install.sh: warning: Python's vtkmodules do not import; the reader tests will fail" >&2
# The .glb tests' readers: assimp (above) and the Khronos glTF validator
# (npm, pinned, under tools/node; Node.js from Debian unless one is there).
command -v npm >/dev/null || $SUDO apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null
npm install --prefix tools/node --no-save --no-package-lock --no-audit --no-fund gltf-validator@2.0.0-dev.3.10 >/dev/null
# TEST dependencies only: tests/sweep/test_slurm.sh starts its own single-node
# Slurm cluster under a temporary folder.  Installed here when missing, and no
# daemon is left enabled or running (a workstation that only grows sponges
# gets no scheduler service); an existing Slurm installation is left alone.
if ! dpkg -s slurm-wlm munge >/dev/null 2>&1; then
  $SUDO apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
  if [ -d /run/systemd/system ]; then $SUDO systemctl disable --now slurmctld slurmd munge >/dev/null 2>&1 || true; fi
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
# The main job on its embedded default: the device in use, then a Crella
# incrustans sponge grown for 50 iterations (Table 1 + the crella preset).
./build/sessile devices
./build/sessile grow --preset crella --iterations 50 --seed 7 --out runs/crella --force
# Coralize's three generators on their defaults (each under a second).
./build/sessile coral lsystem --force
./build/sessile coral venation --force
./build/sessile sponge particles --force
