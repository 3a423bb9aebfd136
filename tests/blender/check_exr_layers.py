# The compositing steps of docs/rendering.md ("Compositing the EXR layers"), headless:
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/check_exr_layers.py \
#       -- --cloudgraph build/cli/cloudgraph --graph tests/blender/exr_layers.json --work /tmp/bl
# renders a cloud to a multi-layer EXR with the CLI, opens it in the compositor's Image node
# and checks that Blender sees the cloud and background layers, and that Alpha Over of the
# cloud layer (premultiplied) over the background gives back the beauty and over a plate gives
# cloud + (1 - alpha) plate. Any failed check exits 1.

import argparse
import json
import os
import shutil
import subprocess
import sys

import bpy

PLATE = (0.2, 0.3, 0.1)  # a constant plate, linear RGB


def fail(message):
    raise SystemExit("check_exr_layers: " + message)


def check(condition, message):
    if not condition:
        fail(message)


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(description="check CloudGraph's EXR layers in Blender")
    p.add_argument("--cloudgraph", required=True, help="the cloudgraph binary")
    p.add_argument("--graph", required=True, help="graph writing blender/layers.exr")
    p.add_argument("--work", required=True, help="scratch directory (emptied first)")
    return p.parse_args(argv)


def run_graph(args):
    """The EXR's path and its size (Blender's Image gives a multi-layer file no size)."""
    shutil.rmtree(args.work, ignore_errors=True)
    out = os.path.join(args.work, "out")
    subprocess.run([args.cloudgraph, "run", args.graph, "--out", out, "-q"], check=True)
    with open(args.graph) as f:
        params = json.load(f)["nodes"]["render"]["params"]
    return os.path.join(out, "blender", "layers.exr"), params["width"], params["height"]


class Compositor:
    """The scene's compositor with an Image node on our EXR; renders one socket at a time to a
    32-bit float EXR (alpha dropped: Composite's Use Alpha off) and reads its pixels back."""

    def __init__(self, path, width, height, work):
        self.work = work
        self.image = bpy.data.images.load(path)
        scene = bpy.context.scene
        scene.use_nodes = True
        self.tree = scene.node_tree
        for node in list(self.tree.nodes):
            self.tree.nodes.remove(node)
        self.source = self.tree.nodes.new("CompositorNodeImage")
        self.source.image = self.image
        self.composite = self.tree.nodes.new("CompositorNodeComposite")
        self.composite.use_alpha = False
        self.pixels = width * height
        scene.render.resolution_x, scene.render.resolution_y = width, height
        scene.render.resolution_percentage = 100
        settings = scene.render.image_settings
        settings.file_format, settings.color_depth, settings.color_mode = "OPEN_EXR", "32", "RGBA"
        scene.view_settings.view_transform = "Standard"
        self.count = 0

    def output(self, name):
        socket = self.source.outputs.get(name)
        check(socket is not None, "the Image node has no output %r: %s"
              % (name, [o.name for o in self.source.outputs]))
        return socket

    def alpha_over(self, background, foreground):
        """Alpha Over as the docs say: Convert Premultiplied off (the cloud is premultiplied)."""
        node = self.tree.nodes.new("CompositorNodeAlphaOver")
        node.use_premultiply = False
        node.premul = 0.0
        self.tree.links.new(background, node.inputs[1])
        self.tree.links.new(foreground, node.inputs[2])
        return node.outputs["Image"]

    def plate(self):
        node = self.tree.nodes.new("CompositorNodeRGB")
        node.outputs[0].default_value = PLATE + (1.0,)
        return node.outputs[0]

    def render(self, socket):
        """RGB of each pixel (bottom row first, as Blender stores them)."""
        for link in list(self.tree.links):
            if link.to_node == self.composite:
                self.tree.links.remove(link)
        self.tree.links.new(socket, self.composite.inputs["Image"])
        self.count += 1
        scene = bpy.context.scene
        scene.render.filepath = os.path.join(self.work, "composite%d.exr" % self.count)
        result = bpy.ops.render.render(write_still=True)
        check(result == {"FINISHED"}, "render: %s" % result)
        pixels = list(bpy.data.images.load(scene.render.filepath).pixels)
        return [pixels[i:i + 3] for i in range(0, len(pixels), 4)]


def close(a, b):
    return abs(a - b) <= 1e-5 * max(1.0, abs(a), abs(b))


def main():
    args = arguments()
    path, width, height = run_graph(args)
    comp = Compositor(path, width, height, args.work)
    check(comp.image.type == "MULTILAYER",
          "Blender reads %s as %s, not a multi-layer EXR" % (path, comp.image.type))
    names = [o.name for o in comp.source.outputs]
    for name in ("cloud", "background"):
        check(name in names, "the Image node shows no layer %r: %s" % (name, names))

    beauty = comp.render(comp.output("Combined"))
    cloud = comp.render(comp.output("cloud"))
    alpha = [p[0] for p in comp.render(comp.output("Alpha"))]
    over_background = comp.render(comp.alpha_over(comp.output("background"), comp.output("cloud")))
    over_plate = comp.render(comp.alpha_over(comp.plate(), comp.output("cloud")))
    check(len(beauty) == comp.pixels and len(over_plate) == comp.pixels,
          "%d pixels, not %d x %d" % (len(beauty), width, height))

    clear = opaque = 0
    for i, (b, c, a, ob, op) in enumerate(zip(beauty, cloud, alpha, over_background, over_plate)):
        for k in range(3):
            check(close(ob[k], b[k]), "pixel %d: cloud over background %s, beauty %s" % (i, ob, b))
            expected = c[k] + (1.0 - a) * PLATE[k]
            check(close(op[k], expected),
                  "pixel %d: cloud over the plate %s, expected %s (cloud %s, alpha %g)"
                  % (i, op, expected, c, a))
        if a == 0.0:
            clear += 1
            check(c == [0.0, 0.0, 0.0], "pixel %d: no alpha but cloud %s" % (i, c))
        opaque += a > 0.99
    check(clear > len(beauty) // 4 and opaque > 10,
          "%d clear and %d opaque pixels: is the cloud in view?" % (clear, opaque))
    print("check_exr_layers: Blender %s reads the layers %s; Alpha Over of the cloud gives the "
          "beauty over its background and cloud + (1 - alpha) plate over a plate"
          % (bpy.app.version_string, names))


main()
