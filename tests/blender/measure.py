"""Held-out error measured in Blender: the original and each LOD posed by Blender's own Armature modifier
(the depsgraph's evaluated meshes), compared as the library's evaluation does (OpenMeshSkinned/Lod/Evaluate.cc,
Eval/SurfaceDistance): per frame, each surface's vertices plus 20,000 points sampled by area, each measured to the
nearest point of the other surface, both directions pooled into one RMS; the mean over the frames, in % of the
original's rest-pose bounding-box diagonal.

How it differs, and why the test allows 10 %: Blender poses the character from its actions' f-curves (quaternion
keys blended per component and normalised) where the library slerps the exporter's per-frame samples, and the
held-out frames fall between frames; the samples come from NumPy's generator, not the library's; the nearest
points come from mathutils' BVH tree rather than the library's TriangleBvh (both exact)."""

import bpy
import numpy
from mathutils import Vector
from mathutils.bvhtree import BVHTree

SAMPLES = 20000


def posed_surface(obj):
    """(points (N, 3), triangles (T, 3)) of \\p obj as the depsgraph has it now, in world space."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        mesh.calc_loop_triangles()
        points = numpy.empty(len(mesh.vertices) * 3)
        mesh.vertices.foreach_get("co", points)
        triangles = numpy.empty(len(mesh.loop_triangles) * 3, dtype=numpy.int64)
        mesh.loop_triangles.foreach_get("vertices", triangles)
    finally:
        evaluated.to_mesh_clear()
    points = points.reshape(-1, 3)
    world = numpy.array(obj.matrix_world)
    points = points @ world[:3, :3].T + world[:3, 3]
    return points, triangles.reshape(-1, 3)


def samples(points, triangles, rng):
    """The surface's vertices and SAMPLES points drawn uniformly by area."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    area = 0.5 * numpy.linalg.norm(numpy.cross(b - a, c - a), axis=1)
    chosen = rng.choice(len(triangles), size=SAMPLES, p=area / area.sum())
    u, v = rng.random(SAMPLES), rng.random(SAMPLES)
    flip = u + v > 1.0
    u[flip], v[flip] = 1.0 - u[flip], 1.0 - v[flip]
    drawn = a[chosen] + (b[chosen] - a[chosen]) * u[:, None] + (c[chosen] - a[chosen]) * v[:, None]
    return numpy.vstack([points, drawn])


def squared_distances(points, surface):
    tree = BVHTree.FromPolygons([Vector(p) for p in surface[0]], surface[1].tolist(), all_triangles=True)
    out = numpy.empty(len(points))
    for i, p in enumerate(points):
        out[i] = tree.find_nearest(Vector(p))[3] ** 2
    return out


def rest_diagonal(obj):
    points = numpy.array([obj.matrix_world @ v.co for v in obj.data.vertices])
    return float(numpy.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def heldout_rms(armature, original, lods, frames, pose):
    """Per LOD, the mean over \\p frames ((clip, seconds), posed by \\p pose) of the pooled RMS, % of the
    diagonal."""
    diagonal = rest_diagonal(original)
    rng = numpy.random.default_rng(1)
    sums = [0.0] * len(lods)
    for clip, seconds in frames:
        pose(clip, seconds)
        reference = posed_surface(original)
        reference_samples = samples(*reference, rng)
        for i, lod in enumerate(lods):
            surface = posed_surface(lod)
            d2 = numpy.concatenate([squared_distances(reference_samples, surface),
                                    squared_distances(samples(*surface, rng), reference)])
            sums[i] += float(numpy.sqrt(d2.mean()))
    return [100.0 * s / len(frames) / diagonal for s in sums]
