#pragma once
// The samples a RawVolumeSpec describes (raw_volume.hpp), read into an
// OpenVDB float grid under the spec's transform.
#include <string>

#include <openvdb/openvdb.h>

#include "core/volume/io/raw_volume.hpp"

namespace weft {

// origin + direction * diag(spacing): a scale map when the direction is the
// identity (plus a translation for an origin), else an affine map.
openvdb::math::Transform::Ptr rawTransform(const RawVolumeSpec& spec);

// Reads the samples into a float grid named spec.gridName with background
// spec.background and transform rawTransform(spec). Throws weft::Error when
// the file is missing, unreadable, corrupt, holds a different number of
// bytes than the spec needs, or holds non-finite floats or doubles beyond
// float range.
openvdb::FloatGrid::Ptr readVolumeSamples(const RawDataSource& source, const RawVolumeSpec& spec);

// A headerless file: the whole of PATH, gzip when it ends in ".gz".
openvdb::FloatGrid::Ptr readRawVolume(const std::string& path, const RawVolumeSpec& spec);

}  // namespace weft
