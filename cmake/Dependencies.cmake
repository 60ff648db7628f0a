# Every dependency comes from Debian 12 packages (scripts/install-deps.sh).
# The order and the pkg-config detours are deliberate; see the comments.
find_package(PkgConfig REQUIRED)

# TBB before OpenVDB: OpenVDB's Find module defines TBB::tbb itself, and TBB's
# config refuses to run after that ("some (but not all) targets ... defined").
find_package(TBB CONFIG REQUIRED)

# OpenVDB ships a Find module, not a config.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

# OpenImageIO's CMake config names /usr/include/opencv4, which only exists with
# libopencv-dev; pkg-config avoids it.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
pkg_check_modules(OPENEXR REQUIRED IMPORTED_TARGET OpenEXR)
# PNG previews through libpng itself (core/image/io/png_writer.hpp).
find_package(PNG REQUIRED)

# OpenColorIO's config sits in /usr/lib/cmake where find_package does not look.
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)

find_package(embree 3 CONFIG REQUIRED)

# OpenSubdiv's config references static libraries Debian does not ship.
find_library(OSD_CPU osdCPU REQUIRED)
find_path(OSD_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)

# Mesh files: OBJ/MTL through tinyobjloader (keeps the file's vertex indices
# and `t crease` tags for subdivision), PLY through Assimp. Assimp's CMake
# config drags in static librt.a and draco; pkg-config links just libassimp.
find_package(tinyobjloader CONFIG REQUIRED)
pkg_check_modules(ASSIMP REQUIRED IMPORTED_TARGET assimp)

find_package(CLI11 CONFIG REQUIRED)
# gzip-compressed raw volumes (weft convert).
find_package(Boost REQUIRED COMPONENTS iostreams)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(Threads REQUIRED)
