#pragma once
// The only header that brings in GL declarations: glad's generated loader.
#include <glad/gl.h>  // IWYU pragma: export
