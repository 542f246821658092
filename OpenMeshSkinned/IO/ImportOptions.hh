#pragma once
/** \file ImportOptions.hh
 *  What import_skinned() is asked to do (ImportOptions) and what it reports having done (ImportReport): on
 *  their own, so that the reader's steps can take them without depending on the reader as a whole.
 */

#include <cstddef>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

struct ImportOptions {
  /** Rescale every vertex's weights to sum to one, whatever the sum (default). FBX and Collada store raw
   *  deformer weights that the authoring tool normalises at run time (Blender's armature modifier does),
   *  so real files often sum to 0.9 or 1.3; the report says how many and the range. With false, sums off
   *  by more than sum_tolerance are an error. A sum of 0, a negative or a non-finite weight is always an
   *  error. */
  bool normalize_weights = true;
  double sum_tolerance = 1e-2;

  /** Read the file in a child process (POSIX fork) under the limits below, so that a reader bug on a
   *  corrupt or hostile file (assimp 5.2's X and MD5 readers crash, or allocate without bound, on some)
   *  ends as an IOError instead of taking the calling process down. Off by default; the command-line tool
   *  turns it on. Call it before your process starts threads (fork copies only the calling thread). */
  bool isolate = false;
  size_t memory_limit_mb = 8192;      ///< address space the isolated reader may use; 0 = no limit
  double time_limit_seconds = 300.0;  ///< wall-clock time the isolated reader may take; 0 = no limit
  /// What the isolated reader printed (assimp, the C library), written to this process's stderr as
  /// "reader: ..." lines; by default it is collected and dropped, so that an error is one line.
  bool show_reader_output = false;
  /** Vertex-animated formats (MD2, MD3, MDL) store whole frames of positions: which one to read (assimp
   *  reads frame 0 when this is negative). import_frame_animation() reads them all. */
  int frame = -1;
  /** Read every frame as one mesh: each stored frame after the first (all_stored_frames, MD2/MD3/MDL) or
   *  each of frame_files (the same mesh in other files) becomes a morph target of the first frame, named
   *  "frame_0001", ... . Done before vertices are welded, so that two vertices are one only when they
   *  coincide in every frame. import_frame_animation() sets these and adds the clip. */
  bool all_stored_frames = false;
  std::vector<std::string> frame_files;
};

/// What the importer did to the data, for the user to read.
struct ImportReport {
  size_t source_meshes = 0;
  size_t source_vertices = 0;  ///< vertices as stored in the file (split at seams)
  size_t welded_vertices = 0;  ///< OpenMesh vertices after welding split copies
  size_t faces = 0;
  size_t degenerate_faces_skipped = 0;    ///< triangles with a repeated vertex after welding
  size_t nonmanifold_vertices_added = 0;  ///< copies made so that faces on complex edges are kept
  size_t unweighted_vertices = 0;         ///< vertices of a skinned mesh with no bone: bound to the mesh's node
  size_t truncated_vertices = 0;          ///< vertices with more than Influences::kCapacity bones
  size_t renormalized_vertices = 0;       ///< vertices whose weight sum was not 1 (rescaled)
  double min_weight_sum = 1.0, max_weight_sum = 1.0;  ///< range of the sums as found in the file
  size_t zero_area_faces = 0;  ///< triangles of zero area kept (three distinct, collinear vertices)
  size_t twin_joints = 0;      ///< joints duplicated because two skins bind the same node differently
  size_t morph_targets = 0;
  size_t joints = 0;
  size_t clips = 0;
  bool rigid = false;  ///< the file had no skin at all; every mesh moves with its node
  std::vector<std::string> warnings;
};

}  // namespace OpenMeshSkinned
