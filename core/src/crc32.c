/* CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), nibble-wise: small and table-free
 * at rest (the 16-entry table is built on the stack per call, cheaper than 4 MB of bits). */
#include "hv/cost_table.h"

uint32_t hv_crc32(uint32_t crc, const void *data, size_t len)
{
    uint32_t nib[16];
    for (uint32_t i = 0; i < 16u; i++) {
        uint32_t c = i;
        for (int k = 0; k < 4; k++) {
            c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
        }
        nib[i] = c;
    }
    const uint8_t *p = (const uint8_t *)data;
    crc = ~crc;
    for (size_t i = 0; i < len; i++) {
        crc ^= p[i];
        crc = (crc >> 4) ^ nib[crc & 15u];
        crc = (crc >> 4) ^ nib[crc & 15u];
    }
    return ~crc;
}
