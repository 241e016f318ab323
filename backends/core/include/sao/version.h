// The library version. Backends check the header's version against the library's at create().
#pragma once

#define SAO_VERSION_MAJOR 0
#define SAO_VERSION_MINOR 1
#define SAO_VERSION_PATCH 0
#define SAO_VERSION ((SAO_VERSION_MAJOR << 16) | (SAO_VERSION_MINOR << 8) | SAO_VERSION_PATCH)

namespace sao {

// The version the library was built with (compare with SAO_VERSION from the header you include).
int libraryVersion();

}  // namespace sao
