"""CloudGraph for Blender: imports a CloudGraph run (its VDB sequence, camera, sun, sky and
ground) as a scene that Cycles renders as CloudGraph's Renderer does.

File > Import > CloudGraph output, or from Python:

    bpy.ops.cloudgraph.import_output(directory="/path/to/out", graph="/path/to/graph.json")

`directory` is the run's --out folder; `graph` the graph it ran, which names the files its
WriteVDB and WriteShot nodes wrote. See docs/user-guide.md, "Blender: the add-on".
"""

bl_info = {
    "name": "CloudGraph",
    "author": "CloudGraph",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > CloudGraph output",
    "description": "Import a CloudGraph run's clouds, camera and lighting",
    "category": "Import-Export",
}

import bpy

from . import operators


def menu_entry(menu, _context):
    menu.layout.operator(operators.CLOUDGRAPH_OT_import_output.bl_idname,
                         text="CloudGraph output (folder + graph)")


def register():
    bpy.utils.register_class(operators.CLOUDGRAPH_OT_import_output)
    bpy.types.TOPBAR_MT_file_import.append(menu_entry)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_entry)
    bpy.utils.unregister_class(operators.CLOUDGRAPH_OT_import_output)
