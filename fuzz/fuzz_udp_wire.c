/* Fuzz target: python-can udp_multicast datagrams as the C transport decodes them
 * (hv_can_udp_wire_decode, msgpack-c; hv/can_udp_wire.h).
 * Properties: no crash, leak or undefined behaviour; a datagram is a frame, malformed or
 * unsupported, nothing else; a decoded frame is a valid classic CAN frame that encodes and
 * decodes back to itself (id, flags, dlc, data). */
#include <stdlib.h>
#include <string.h>

#include <msgpack.h>

#include "fuzz_support.h"
#include "hv/can_udp_wire.h"

static void decoded_frame_ok(const hv_can_frame_t *f)
{
    int ext = (f->flags & HV_CAN_FLAG_EXT) != 0;
    if (f->dlc > HV_CAN_MAX_DLC || f->id > (ext ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK) ||
        (f->flags & ~(HV_CAN_FLAG_EXT | HV_CAN_FLAG_RTR | HV_CAN_FLAG_ERR)) != 0)
        hv_fuzz_fail("decoded an invalid frame: id %x dlc %u flags %x", (unsigned)f->id,
                     (unsigned)f->dlc, (unsigned)f->flags);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    msgpack_zone zone;
    if (!msgpack_zone_init(&zone, MSGPACK_ZONE_CHUNK_SIZE))
        abort();
    hv_can_frame_t f, back;
    memset(&f, 0, sizeof f);
    hv_status_t st = hv_can_udp_wire_decode(data, size, &zone, &f);
    if (st == HV_OK) {
        decoded_frame_ok(&f);
        uint8_t buf[HV_CAN_UDP_MAX_DATAGRAM];
        size_t len;
        if (hv_can_udp_wire_encode(&f, 1.5, buf, sizeof buf, &len) != HV_OK)
            hv_fuzz_fail("a decoded frame does not encode");
        memset(&back, 0, sizeof back);
        if (hv_can_udp_wire_decode(buf, len, &zone, &back) != HV_OK)
            hv_fuzz_fail("our own encoding of a decoded frame is refused");
        if (back.id != f.id || back.flags != f.flags || back.dlc != f.dlc ||
            memcmp(back.data, f.data, f.dlc) != 0)
            hv_fuzz_fail("a frame changed through encode and decode");
    } else if (st != (hv_status_t)HV_CAN_ERR_MALFORMED &&
               st != (hv_status_t)HV_CAN_ERR_UNSUPPORTED) {
        hv_fuzz_fail("decode returned %d", (int)st);
    }
    msgpack_zone_destroy(&zone);
    return 0;
}
