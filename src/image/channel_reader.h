// Reading image files of any format is OpenImageIO's job, and OpenImageIO is heavy to load: a
// program linked against Debian's build of it maps some 260 shared libraries and runs their static
// initialisers before main (about half a second). Only `compare` and the tests read images, so the
// reader lives in a module of its own (src/image/oiio/, built as shadowref_image_reader.so) that
// readChannelImage loads on first use; rendering, checking and --help never pay for it.
#pragma once

#include <string>

#include "image/channel_image.h"

namespace shadowref {

// Reads an image file that checkFile (channel_image.cpp) has already found to be a regular file of
// bounded size with sound EXR headers; see readChannelImage for the rest of the contract.
using ChannelReader = ChannelImage (*)(const std::string& path, const ReadLimits& limits);

// The module's one entry point: a C name, so that dlsym finds it, returning the reader.
extern "C" ChannelReader shadowref_channel_reader_v1();

}  // namespace shadowref
