// A walk over a PNG file's chunks before any image library reads it. libpng allocates a chunk's
// buffer from the length the chunk declares (its user chunk limit unset, as OpenImageIO leaves
// it), so a 200-byte file declaring a 1 GB text chunk allocates 1 GB: the walk refuses a chunk
// that does not fit in the file, as the PNG specification's lengths must ([PNG 2003, §5.3]).
#pragma once

#include <string>
#include <string_view>

namespace shadowref {

// Whether the bytes begin with PNG's eight-byte signature.
bool looksLikePng(std::string_view bytes);

// "" when every chunk from the signature to IEND declares a length of at most 2^31 - 1 that fits,
// with its type and CRC, in the bytes left; else what is wrong, naming the chunk and its byte
// offset. A file that ends before IEND with its chunks whole is left to the reader.
std::string checkPngChunks(std::string_view bytes);

}  // namespace shadowref
