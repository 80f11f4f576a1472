#pragma once
/// @file Fast CBOR codec of LSM files (private to libmapfuse/src/io). The general path builds a
/// JSON tree (nlohmann) and reads it through JsonView: 8 ms per driven km on this machine, most
/// of it allocations, and the chain reads or writes every LSM five times (georef in and out,
/// align in and out, aggregate in). This codec goes straight between the bytes and the structs:
/// - `encodeLsmCbor` writes exactly the bytes of `nlohmann::json::to_cbor(lsmToJson(lsm))`;
/// - `decodeLsmCbor` reads what that writer produces (and any CBOR of the same schema with
///   definite lengths) and returns nullopt for anything else, unusual or invalid: unknown or
///   duplicate keys, null values, other types, values out of range. readLsm then takes the
///   general path, which accepts or rejects the file with its precise message, so both paths
///   accept the same files, give the same LSM and fail with the same errors.
#include <optional>
#include <string>
#include <string_view>

#include "mapfuse/core/lsm.hpp"

namespace mapfuse::io::detail {

/// @brief The LSM as CBOR, byte for byte what nlohmann::json::to_cbor(lsmToJson(lsm)) gives.
std::string encodeLsmCbor(const Lsm& lsm);

/// @brief Decodes a CBOR LSM; nullopt when the general reader must judge the bytes. The result
/// is not yet checked by validateLsm.
std::optional<Lsm> decodeLsmCbor(std::string_view bytes);

}  // namespace mapfuse::io::detail
