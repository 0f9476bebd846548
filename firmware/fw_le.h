/* Little-endian fields of the firmware's binary formats (the plan image, plan_image.h; the
 * journal's records, fw_journal.h): byte by byte, so alignment and the host's byte order
 * never matter. Pure; shared by the host's tools and tests and the firmware. */
#ifndef HV_FW_LE_H
#define HV_FW_LE_H

#include <stdint.h>

static inline void hv_fw_put_u16(uint8_t *b, uint32_t v)
{
    b[0] = (uint8_t)(v & 0xFFu);
    b[1] = (uint8_t)((v >> 8) & 0xFFu);
}

static inline void hv_fw_put_u32(uint8_t *b, uint32_t v)
{
    hv_fw_put_u16(b, v & 0xFFFFu);
    hv_fw_put_u16(b + 2, v >> 16);
}

static inline uint32_t hv_fw_get_u16(const uint8_t *b)
{
    return (uint32_t)b[0] | ((uint32_t)b[1] << 8);
}

static inline uint32_t hv_fw_get_u32(const uint8_t *b)
{
    return hv_fw_get_u16(b) | (hv_fw_get_u16(b + 2) << 16);
}

#endif /* HV_FW_LE_H */
