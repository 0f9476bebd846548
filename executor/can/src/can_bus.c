/* Transport-independent part of hv/can_bus.h: argument checks, dispatch, accessors. */
#include "hv/can_bus.h"

#include <string.h>

hv_status_t hv_can_send(hv_can_bus_t *bus, const hv_can_frame_t *frame, int timeout_ms)
{
    if (!bus || !frame)
        return HV_ERR_ARG;
    if (!bus->ops)
        return (hv_status_t)HV_CAN_ERR_CLOSED;
    int ext = (frame->flags & HV_CAN_FLAG_EXT) != 0;
    if (frame->dlc > HV_CAN_MAX_DLC || frame->id > (ext ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK) ||
        ((frame->flags & HV_CAN_FLAG_RTR) && (frame->flags & HV_CAN_FLAG_ERR))) {
        bus->stats.tx_failures++;
        return (hv_status_t)HV_CAN_ERR_FRAME;
    }
    hv_status_t st = bus->ops->send(bus, frame, timeout_ms);
    if (st == HV_OK)
        bus->stats.tx_frames++;
    else
        bus->stats.tx_failures++;
    return st;
}

hv_status_t hv_can_recv(hv_can_bus_t *bus, hv_can_frame_t *frame, int timeout_ms)
{
    if (!bus || !frame)
        return HV_ERR_ARG;
    if (!bus->ops)
        return (hv_status_t)HV_CAN_ERR_CLOSED;
    return bus->ops->recv(bus, frame, timeout_ms);
}

void hv_can_close(hv_can_bus_t *bus)
{
    if (!bus || !bus->ops)
        return;
    bus->ops->close(bus);
    bus->ops = NULL;
    bus->rx_fd = -1;
    bus->tx_fd = -1;
}

hv_status_t hv_can_get_stats(const hv_can_bus_t *bus, hv_can_stats_t *out)
{
    if (!bus || !out)
        return HV_ERR_ARG;
    if (!bus->ops)
        memset(out, 0, sizeof *out);
    else
        *out = bus->stats;
    return HV_OK;
}

int hv_can_fd(const hv_can_bus_t *bus)
{
    return (bus && bus->ops) ? bus->rx_fd : -1;
}

const char *hv_can_name(const hv_can_bus_t *bus)
{
    return (bus && bus->ops) ? bus->name : "closed";
}

int hv_can_last_errno(const hv_can_bus_t *bus)
{
    return bus ? bus->last_errno : 0;
}

int hv_can_filter_match(const hv_can_filter_t *filters, size_t n, const hv_can_frame_t *frame)
{
    if (n == 0)
        return 1;
    int ext = (frame->flags & HV_CAN_FLAG_EXT) != 0;
    for (size_t i = 0; i < n; i++) {
        if ((filters[i].ext != 0) != ext)
            continue;
        if ((frame->id & filters[i].mask) == (filters[i].id & filters[i].mask))
            return 1;
    }
    return 0;
}
