"""The add-on's operator: bpy.ops.cloudgraph.import_output(directory=, graph=)."""

import bpy

from . import outputs, scene


class CLOUDGRAPH_OT_import_output(bpy.types.Operator):
    """Import a CloudGraph run: its VDB sequence (with motion blur from 'vel'), camera, sun,
    sky and ground, as its Renderer saw them"""

    bl_idname = "cloudgraph.import_output"
    bl_label = "Import CloudGraph output"
    bl_options = {"REGISTER", "UNDO"}

    directory: bpy.props.StringProperty(name="Run folder", subtype="DIR_PATH",
                                        description="the run's --out folder")
    graph: bpy.props.StringProperty(name="Graph", subtype="FILE_PATH",
                                    description="the graph file the run ran")
    motion_blur: bpy.props.BoolProperty(name="Motion blur", default=True,
                                        description="blur by the VDBs' velocity grid 'vel'")

    def execute(self, context):
        try:
            _, vdb_pattern = outputs.one_writer(self.graph, "WriteVDB")
            _, shot_file = outputs.one_writer(self.graph, "WriteShot")
            sequence = outputs.vdb_sequence(self.directory, vdb_pattern)
            shot = outputs.read_shot(self.directory, shot_file)
        except outputs.OutputError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        made = scene.import_run(sequence, shot, self.motion_blur)
        self.report({"INFO"}, "CloudGraph: frames %d-%d, %d VDBs, motion blur %s"
                    % (shot["frames"]["start"], shot["frames"]["end"], len(sequence),
                       "on" if made["motion_blur"] else "off (no 'vel' grid)"))
        return {"FINISHED"}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}
