// GL as crowdprof sees it: glad's 4.5 core loader (generated at build time,
// render.cmake) and error checks. Never include this next to GL/osmesa.h: its
// GL/gl.h clashes with glad's header (osmesa_context.cpp keeps to itself).
#pragma once

#include <string>
#include <string_view>

#include <glad/gl.h>

namespace crowdprof {

// "GL_INVALID_OPERATION", or "0x1234" for a code GL does not name.
std::string gl_error_name(GLenum error);

// Throws GlError "GL error GL_INVALID_VALUE during <where>" for the first
// pending error (and clears the rest); does nothing when there is none.
void check_gl(std::string_view where);

}  // namespace crowdprof
