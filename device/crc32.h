// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, init and final xor 0xFFFFFFFF):
// the checksum of the HandHIRO packets (docs/handhiro-protocol.md). crc32("123456789")
// is 0xCBF43926.
#pragma once

#include <cstddef>
#include <cstdint>

namespace palpation::device {

std::uint32_t crc32(const std::uint8_t* data, std::size_t size);

}  // namespace palpation::device
