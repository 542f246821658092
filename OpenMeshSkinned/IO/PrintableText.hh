#pragma once
/** \file PrintableText.hh
 *  Text from a file made fit for a terminal and for glTF's JSON: readers quote names and bytes of the file
 *  back in their messages, and a corrupt file's bytes are not text.
 */

#include <cstddef>
#include <string>
#include <string_view>

namespace OpenMeshSkinned {

/** \p text as valid UTF-8 without control characters: each byte that starts no valid UTF-8 sequence, and
 *  each control character, becomes '?' (line breaks and tabs a space). */
std::string printable_text(std::string_view text);

/** printable_text() of \p text as one line of at most \p max_bytes (cut on a character boundary, with
 *  " [...]" after the cut); trailing white space removed. */
std::string printable_line(std::string_view text, size_t max_bytes = 240);

}  // namespace OpenMeshSkinned
