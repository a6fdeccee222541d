# Made the two Blender OBJ files in this folder (Blender 3.4.1, its built-in exporter, defaults:
# forward -Z, up Y; normals and UVs on, flat shading "s 0"):
#   blender -b --factory-startup --python tests/data/obj/blender_export.py
# Writes blender_torus.obj (12 x 8 quads, R = 1, r = 0.35) and blender_icosphere.obj
# (2 subdivisions, radius 1) next to this script.
import os
import bpy

here = os.path.dirname(os.path.abspath(__file__))
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_torus_add(major_segments=12, minor_segments=8, major_radius=1.0, minor_radius=0.35)
bpy.ops.wm.obj_export(filepath=os.path.join(here, "blender_torus.obj"), export_normals=True, export_uv=True,
                      export_materials=False, export_triangulated_mesh=False)
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=1.0)
bpy.ops.wm.obj_export(filepath=os.path.join(here, "blender_icosphere.obj"), export_normals=True, export_uv=True,
                      export_materials=False)
