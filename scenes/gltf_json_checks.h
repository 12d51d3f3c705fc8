#pragma once
// The JSON checks made before tinygltf parses a file: what tinygltf would
// index or read unchecked (buffer, bufferView and accessor sizes, the
// accessors a mesh names), what it reports without saying where (a
// top-level array of the wrong kind), and the limits (nesting depth,
// element counts, required extensions, every URI through the sandbox).
// Their messages name the JSON element ("bufferView 2", "mesh 'car' (0)
// primitive 1").
#include <cstddef>

#include "scenes/gltf_uri_sandbox.h"

namespace sb::gltf {

// Throws InputError naming `file` and the element at fault.
void check_gltf_json(const std::string& file, const UriSandbox& sandbox, const unsigned char* data,
                     size_t size);

}  // namespace sb::gltf
