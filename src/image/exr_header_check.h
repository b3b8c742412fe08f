// OpenEXR allocates each header attribute at the size its header declares, before OpenImageIO hands
// back an image spec: a 407-byte file declaring a 1.85 GB attribute made `compare` allocate that
// much. This walk over the headers, made before OpenImageIO opens the file, refuses any attribute
// that claims more bytes than the file has left, so OpenEXR's allocations stay within the file's
// size. OpenEXR reads the attributes of known types by their own structure, not by the declared
// size (a channel list until its empty name, an int as 4 bytes), so the walk also checks that each
// known type's value ends exactly where its size says; otherwise OpenEXR would read the next
// attribute from another place than this walk did, and trust a size nobody checked. Last, the
// chunk offset table OpenEXR allocates from the data window (or from chunkCount) must fit in the
// file, 8 bytes per chunk.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace shadowref {

// True when `bytes` begins with the OpenEXR magic number (76 2f 31 01).
bool looksLikeExr(std::string_view bytes);

// Walks the attribute lists of an OpenEXR file's header (every part's, for a multi-part file):
// name\0 type\0 int32 size, then `size` bytes. Returns "" when every attribute fits in the file,
// every known type's value has the size OpenEXR reads, and every part's offset table fits,
// otherwise what is wrong ("attribute 'x' declares 1850000000 bytes, more than the 380 left in
// the file"). `bytes` is the whole file.
std::string checkExrHeaders(std::string_view bytes);

}  // namespace shadowref
