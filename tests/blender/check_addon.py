# The Blender add-on, installed from the zip the build makes as a user installs it, imports a
# run of the default scene (Figure 6, with a small primitive) and Cycles renders a frame of
# it, motion blur on, as CloudGraph's Renderer does: the silhouettes' intersection over union
# at least 0.85 and the mean luminance of the cloud within 0.75-1.33 of ours
# (build/bench/image_error).
#
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/check_addon.py --
#       --cloudgraph build/cli/cloudgraph --image-error build/bench/image_error
#       --zip build/integrations/blender/cloudgraph_blender.zip
#       --graph graphs/figure6_towering_cumulus.json --work /tmp/addon
import argparse
import os
import re
import shutil
import subprocess
import sys

import bpy

FRAME = 300  # 60% of Figure 6's run: a tower 4 km high
SIZE = (96, 72)
SAMPLES = 32


def fail(message):
    print("check_addon: FAILED: " + message, file=sys.stderr)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def arguments():
    p = argparse.ArgumentParser()
    for name in ("--cloudgraph", "--image-error", "--zip", "--graph", "--work"):
        p.add_argument(name, required=True)
    return p.parse_args(sys.argv[sys.argv.index("--") + 1:])


# The golden tests' small primitive (tests/golden/GoldenSpecs.cc): the default scene in
# seconds, also under the sanitizers, whose build runs this test too.
SMALL_PRIMITIVE = ["primitive.frames=40", "primitive.width=400", "primitive.height=700",
                   "primitive.sourceHeight=100", "primitive.sourceRadius=125",
                   "primitive.sourceHumidity=1"]


def run_graph(args, out):
    """Frames FRAME - 1 and FRAME of the default scene with a small primitive: the VDBs (with
    'vel'), the shot, and CloudGraph's own render of FRAME as an EXR, all at the test's image
    size."""
    small = [a for s in SMALL_PRIMITIVE for a in ("--set", s)]
    subprocess.run([args.cloudgraph, "run", args.graph, "--out", out, *small,
                    "--cache", os.path.join(args.work, "cache"),
                    "--frames", "%d:%d" % (FRAME - 1, FRAME),
                    "--only", "vdb", "--only", "shot", "--only", "image",
                    "--set", "vdb.every=1", "--set", "vdb.firstFrame=%d" % (FRAME - 1),
                    "--set", "render.width=%d" % SIZE[0], "--set", "render.height=%d" % SIZE[1],
                    "--set", "image.file=figure6/ours.####.exr", "-q"], check=True)
    return os.path.join(out, "figure6", "ours.%04d.exr" % FRAME)


def install_addon(zip_path):
    """Preferences > Add-ons > Install..., then tick it."""
    bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
    bpy.ops.preferences.addon_enable(module="cloudgraph_blender")
    check(hasattr(bpy.ops.cloudgraph, "import_output"), "the add-on has no import_output")


def check_import(out, graph):
    for obj in list(bpy.data.objects):  # the factory scene's cube, camera and light
        bpy.data.objects.remove(obj)
    result = bpy.ops.cloudgraph.import_output(directory=out, graph=graph)
    check(result == {"FINISHED"}, "import_output: %s" % result)
    scene = bpy.context.scene
    cloud = bpy.data.objects["CloudGraph cloud"]
    camera = scene.camera
    check(cloud.type == "VOLUME" and cloud.data.frame_start == FRAME - 1,
          "the volume plays from frame %d" % cloud.data.frame_start)
    check(cloud.data.velocity_grid == "vel" and cloud.data.velocity_unit == "SECOND",
          "velocity grid %r in %s" % (cloud.data.velocity_grid, cloud.data.velocity_unit))
    check(scene.render.use_motion_blur, "motion blur is off")
    check((scene.frame_start, scene.frame_end) == (0, 491),
          "frames %d-%d" % (scene.frame_start, scene.frame_end))
    check(abs(scene.render.fps / scene.render.fps_base - 0.5) < 1e-9,
          "%g frames per second, not 1 / timeStep" % (scene.render.fps / scene.render.fps_base))
    keys = camera.animation_data.action.fcurves.find("location", index=0).keyframe_points
    check(len(keys) == 492, "%d camera keys for 492 frames" % len(keys))
    return cloud


def render(work):
    """Cycles, the cloud over nothing (the ground a holdout that still lights it), linear."""
    scene = bpy.context.scene
    scene.frame_set(FRAME)
    scene.cycles.samples = SAMPLES
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.render.film_transparent = True
    bpy.data.objects["CloudGraph ground"].is_holdout = True
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = os.path.join(work, "blender.exr")
    bpy.ops.render.render(write_still=True)
    return scene.render.filepath


def compare(image_error, blender, ours):
    line = subprocess.run([image_error, "--layer", "cloud", blender, ours], check=True,
                          capture_output=True, text=True).stdout
    values = dict(re.findall(r"(\w+)=([0-9.e+-]+)", line))
    iou, ratio = float(values["iou"]), float(values["ratio"])
    print("check_addon: Cycles against CloudGraph, frame %d: %s" % (FRAME, line.strip()))
    check(int(values["pixels"]) > 300, "only %s cloud pixels" % values["pixels"])
    check(iou >= 0.85, "silhouette IoU %.3f < 0.85" % iou)
    check(0.75 <= ratio <= 1.33, "mean cloud luminance ratio %.3f outside 0.75-1.33" % ratio)


def main():
    args = arguments()
    shutil.rmtree(os.path.join(args.work, "out"), ignore_errors=True)
    os.makedirs(args.work, exist_ok=True)
    out = os.path.join(args.work, "out")
    ours = run_graph(args, out)
    install_addon(args.zip)
    check_import(out, os.path.abspath(args.graph))
    compare(args.image_error, render(args.work), ours)
    print("check_addon: the add-on's scene renders in Cycles %s as CloudGraph's Renderer does"
          % bpy.app.version_string)


main()
