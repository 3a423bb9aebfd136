# WriteCamera's .chan in Blender, as the user guide's pipeline chapter says to bring it in:
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/check_chan_camera.py -- \
#       --cloudgraph build/cli/cloudgraph --graph tests/blender/camera_keys.json --work /tmp/bl
# runs the graph, imports the .chan with Blender's bundled Nuke .chan add-on ("Make Z up",
# rotation order ZXY) onto a camera, and checks at every key that Blender's camera puts world
# points on the pixels CloudGraph's camera (computed here from the graph's keys) puts them,
# within a tenth of a pixel. Any failed check exits 1.

import argparse
import json
import math
import os
import shutil
import subprocess
import sys

import addon_utils
import bpy
import mathutils
from bpy_extras.object_utils import world_to_camera_view


def fail(message):
    raise SystemExit("check_chan_camera: " + message)


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(description="check a CloudGraph .chan camera in Blender")
    p.add_argument("--cloudgraph", required=True)
    p.add_argument("--graph", required=True)
    p.add_argument("--work", required=True)
    return p.parse_args(argv)


def pixel_of(key, up_hint, width, height, point):
    """CloudGraph's pinhole: view toward the look-at, up from cameraUp, vertical fov."""
    position = mathutils.Vector(key["position"])
    forward = (mathutils.Vector(key["lookAt"]) - position).normalized()
    right = forward.cross(mathutils.Vector(up_hint)).normalized()
    up = right.cross(forward)
    d = point - position
    t = math.tan(math.radians(key["fov"]) / 2)
    sx = d.dot(right) / d.dot(forward) / (t * width / height)
    sy = d.dot(up) / d.dot(forward) / t
    return (sx + 1) / 2 * width, (1 - sy) / 2 * height


def main():
    args = arguments()
    shutil.rmtree(args.work, ignore_errors=True)
    out = os.path.join(args.work, "out")
    subprocess.run([args.cloudgraph, "run", args.graph, "--out", out, "-q"], check=True)
    with open(args.graph) as f:
        render = json.load(f)["nodes"]["render"]["params"]
    width, height = render["width"], render["height"]
    numbers = render["cameraKeys"]
    keys = [{"frame": int(numbers[i]), "position": numbers[i + 1:i + 4],
             "lookAt": numbers[i + 4:i + 7], "fov": numbers[i + 7]}
            for i in range(0, len(numbers), 8)]

    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    data = bpy.data.cameras.new("shot")
    camera = bpy.data.objects.new("shot", data)
    scene.collection.objects.link(camera)
    bpy.context.view_layer.objects.active = camera
    addon_utils.enable("io_anim_nuke_chan", default_set=True)
    # The sensor's height fits the image's aspect, so the vertical field of view is the file's.
    bpy.ops.import_scene.import_chan(filepath=os.path.join(out, "blender", "shot.chan"),
                                     z_up=True, rotation_order="ZXY",
                                     sensor_width=32.0, sensor_height=32.0 * height / width)
    worst = 0.0
    for key in keys:
        scene.frame_set(key["frame"])
        look = mathutils.Vector(key["lookAt"])
        for offset in [(0, 0, 0), (400, 0, 300), (-600, 200, -250), (250, -300, 500)]:
            point = look + mathutils.Vector(offset)
            expected = pixel_of(key, render["cameraUp"], width, height, point)
            ndc = world_to_camera_view(scene, camera, point)
            got = (ndc.x * width, (1 - ndc.y) * height)
            error = math.hypot(got[0] - expected[0], got[1] - expected[1])
            worst = max(worst, error)
            if error > 0.1:
                fail("frame %d, point %s: Blender puts it at pixel (%.2f, %.2f), CloudGraph at "
                     "(%.2f, %.2f)" % (key["frame"], tuple(point), *got, *expected))
    print("check_chan_camera: %d keys, worst %.2e px" % (len(keys), worst))


main()
