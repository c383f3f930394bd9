#!/usr/bin/env python3
"""Reads a mesh, parameterizes it with ICM, writes it with its UVs and prints the distortion.

    PYTHONPATH=build/python /usr/bin/python3 examples/python_example.py \
        examples/data/three_peaks.off three_peaks_uv.obj

The output's extension names its format: .obj, .ply, or .gltf/.glb when icm.HAS_GLTF.
"""

import sys

import icm


def main(argv):
    if len(argv) != 3:
        print("usage: python_example.py INPUT OUTPUT.obj|.ply|.gltf|.glb", file=sys.stderr)
        return 2
    try:
        V, F, repairs = icm.read_mesh(argv[1])
        for repair in repairs:
            print("repaired:", repair)
        result = icm.parameterize(V, F)
        icm.write_mesh(argv[2], V, F, result.uv, result.fuv)
    except icm.Error as error:
        print("python_example:", error, file=sys.stderr)
        return 1
    report = result.report
    print(f"{argv[1]}: {report['vertices']} vertices, {result.charts} charts, {report['cones']} cones, "
          f"{len(result.seams)} seam edges -> {argv[2]}")
    measures = icm.measure_distortion(V, F, result.uv, result.fuv)
    for key in ("flipped_faces", "log_area_distortion", "qc_mean", "conformality"):
        print(f"  {key}: {measures[key]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
