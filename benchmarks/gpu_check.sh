#!/bin/bash
# The rasterising paths (camera rig, depthbuffer-plane lidar) and simulate's default run on a GPU host.
# Needs seatwin installed and an EGL vendor driver (libglvnd: libegl1 libgl1 libopengl0); where EGL does not find
# the NVIDIA driver by itself: export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/share/glvnd/egl_vendor.d/10_nvidia.json
# Figures: docs/validation.md, "GPU figures". Writes each script's output to ${OUT:-.}/<name>.txt.
set -u
out=${OUT:-.}
here=$(dirname "$0")
{ nvidia-smi -L; nproc; python3 -V; } 2>&1 | tee "$out/machine.txt"
python3 -c "from seatwin.render.context import create_context, renderer_name; print('GL_RENDERER:', renderer_name(create_context()))" \
    2>&1 | tee -a "$out/machine.txt"
timeout 150 python3 "$here/camera.py" 20 2>&1 | tee "$out/camera.txt" | tail -3
timeout 200 python3 "$here/depthbuffer.py" --sweeps 10 --repeats 2 --plane-sweeps 10 2>&1 | tee "$out/depthbuffer.txt" | tail -3
timeout 120 python3 "$here/simulate.py" --sensors lidar,camera --duration 30 2>&1 | tee "$out/simulate.txt" | tail -3
