"""What benchmark/tables.py runs and where: the meshes and methods of each run, the sections
and the runs they read, and where the meshes, the repository and its files are.

Imported by tables.py and its other modules (tables_runs.py, tables_render.py,
tables_cones.py), which find each other in benchmark/ because tables.py is run from there.
"""

import os

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# The meshes of the tables (file names in the mesh directories).
DISKS = ["nefertiti.off", "three_peaks.off", "mushroom.off", "lion-head.off", "camelhead.off",
         "mannequin-devil.off", "horse.obj"]
OTHER_DISKS = ["mesh_with_border.off", "cylinder_locally_refined.off"]
NOT_DISKS = ["sphere966.off", "cow.off", "bull.off", "rotor.off", "elk.off", "knot1.off",
             "eight.off", "femur.off", "elephant.off", "pig.off", "head.off",
             "mech-holes-shark.off", "camel.off", "bear.off"]
# The largest surfaces get only ICM's rows (run icm): CGAL's methods on their cuts, ARAP above
# all, would take most of the time of the whole run.
BIG_SURFACES = ["armadillo.off", "bunny00.off", "refined_elephant.off"]
CLOSED_GENUS_0 = ["sphere966.off", "cow.off", "bull.off", "camel.off", "bear.off"]
# What the default mesh lists leave out, for the header of a section: (run, text).
LEFT_OUT = {
    "nondisk": ("all", "armadillo, bunny00 and refined_elephant left out to keep the whole "
                "run within 15 minutes (their ICM rows are in Every surface)"),
    "opened": ("opened", "armadillo and bunny00 left out to keep the whole run within 15 "
               "minutes (ARAP runs into the time limit on them)"),
}
# icm_param --boundary square; the circles are compare's icm_circle_domain rows (on a disk
# the circle domain is the circle border).
BORDER_SHAPES = [("three_peaks.off", "square"), ("lion-head.off", "square"),
                 ("horse.obj", "square")]
OPENED_METHODS = "icm_free_boundary,lscm,arap,dcm,mvc"
# Every energy through ICM::parameterize on surfaces that are not disks.
SURFACE_ENERGY_MESHES = ["sphere966.off", "pig.off", "cow.off", "eight.off", "elk.off",
                         "rotor.off", "femur.off", "elephant.off", "head.off",
                         "mech-holes-shark.off", "knot1.off"]
SURFACE_ENERGY_METHODS = "icm,icm_u_square,icm_area,icm_angle,icm_log_area"

# Area distortion against the cone count, with the entropy's cone angles (icm_cones_N, and
# icm for the default) and with u-square's (icm_u_square_cones_N, icm_u_square).
CONE_MESHES = CLOSED_GENUS_0 + ["armadillo.off", "bunny00.off", "eight.off", "femur.off"]
CONE_COUNTS = [4, 8, 16, 32]
CONE_ENERGIES = [("entropy", "icm_cones_", "icm"), ("u-square", "icm_u_square_cones_", "icm_u_square")]
CONE_METHODS = ",".join([f"{prefix}{n}" for _, prefix, _ in CONE_ENERGIES for n in CONE_COUNTS] +
                        [default for _, _, default in CONE_ENERGIES])

# The README's few rows: ICM's default call against CGAL's LSCM and ARAP (on ICM's cut where
# ICM cuts), on disks and closed meshes.
SUMMARY_MESHES = ["nefertiti.off", "three_peaks.off", "camelhead.off", "sphere966.off", "cow.off",
                  "bunny00.off"]
SUMMARY_METHODS = ["icm", "lscm", "arap"]
# Sections that go into the README rather than the document of --doc.
README_SECTIONS = ["summary"]

SECTIONS = {  # section: the runs it reads
    "disks": ["all"], "energies": ["all"], "nondisk": ["all"], "surfaces": ["all", "icm"],
    "surface-energies": ["senergies"], "opened": ["opened"], "border": ["all", "border"],
    "scaling": [], "scaling-bff": [], "bff-disks": [], "scaling-short": ["scaling"], "cones": ["cones"],
    "summary": ["summary"],
    "reading": [],
}
# The commands that write the series of sections scaling-bff and bff-disks (scaling.sh with
# BFF's command line beside ICM; run from the repository's root, BFF built apart).
SCALING_BFF_COMMAND = "BFF=.../bff-command-line KMAX=3 NAME=scaling_bff bash benchmark/scaling.sh"
BFF_DISKS_COMMAND = ('MESHES="nefertiti.off mesh_with_border.off three_peaks.off mushroom.off '
                     'cylinder_locally_refined.off lion-head.off mannequin-devil.off camelhead.off '
                     'horse.obj" (their paths) RUNS=5 BFF=.../bff-command-line NAME=bff_disks '
                     'bash benchmark/scaling.sh build/benchmark/compare doc/figures')
# The command that writes the figures of section reading (run from the repository's root).
READING_COMMAND = ("build/benchmark/icm_kernels --benchmark_filter=read_triangle_mesh "
                   "--benchmark_repetitions=3 --benchmark_report_aggregates_only=true "
                   "--benchmark_out=doc/figures/reading.json --benchmark_out_format=json")
REGISTRY_METRICS = ["icm_free_boundary", "icm_vertex_scaling", "icm_inversive_distance",
                    "icm_circle_packing"]
CGAL = ["lscm", "arap", "dcm", "dac", "mvc"]
ENERGIES = ["icm_u_square", "icm_area", "icm_angle", "icm_log_area"]


# ---------------------------------------------------------------- where the meshes are

def mesh_dirs(extra):
    dirs = list(extra)
    if os.environ.get("ICM_MESH_DIR"):
        dirs.append(os.environ["ICM_MESH_DIR"])
    dirs += [os.path.join(ROOT, "..", "shared", "data", "meshes"), "/work/shared/data/meshes",
             os.path.join(ROOT, "examples", "data")]
    return dirs


def find_mesh(name, dirs):
    if os.sep in name or os.path.isfile(name):
        return name
    for d in dirs:
        path = os.path.join(d, name)
        if os.path.isfile(path):
            return os.path.normpath(path)
    return None


def face_count(path):
    """Faces of an OFF (its header) or OBJ (its f lines) file; 0 when unknown."""
    try:
        with open(path, errors="replace") as f:
            if path.endswith(".obj"):
                return sum(1 for line in f if line.startswith("f "))
            words = []
            for line in f:
                line = line.split("#")[0].strip()
                if line:
                    words += line.split()
                if len(words) >= 3 and not words[0].isalpha():
                    return int(words[1])
                if len(words) >= 4:
                    return int(words[2])
    except (OSError, ValueError):
        pass
    return 0


def relative(path):
    """`path` relative to the repository when it is inside it, else absolute."""
    path = os.path.abspath(path)
    return os.path.relpath(path, ROOT) if path.startswith(ROOT + os.sep) else path

