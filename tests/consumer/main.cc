// A user's program: decimate a generated skinned leg with the installed library.
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <iostream>

int main() {
  using Mesh = OpenMeshSkinned::SkinnedMesh;
  Mesh mesh = OpenMeshSkinned::make_bending_cylinder(16, 16);
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  if (!dec.initialize()) return 1;
  const size_t before = mesh.n_faces();
  dec.decimate_to_faces(0, before / 4);
  mesh.garbage_collection();
  std::cout << before << " -> " << mesh.n_faces() << "\n";
  return mesh.n_faces() < before ? 0 : 1;
}
