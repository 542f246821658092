#pragma once
/** \file IOError.hh
 *  The one exception the readers and writers throw. */

#include <stdexcept>

namespace OpenMeshSkinned {

/// An input or output file that cannot be used; what() is one line: "<file>: <problem>".
class IOError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace OpenMeshSkinned
