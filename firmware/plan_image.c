/* The plan image (see plan_image.h): one table of fields per record, read by the writer
 * and written by the reader, so the two cannot disagree on the order. */
#include "plan_image.h"

#include <math.h>
#include <string.h>

#include "fw_le.h"
#include "fw_status.h"
#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/fruit_id.h"

#define HEADER_F64 29u
#define STOP_F64   5u
#define PICK_F64   12u

/* One f64 of the image: a double of the plan (data the host prepared, never computed
 * with here) or a field in the executor's real type (hv/exec_real.h: float on the
 * firmware), converted as its record arrives, so never per step. */
typedef struct field {
    double *d;
    hv_exec_real_t *r;
} field_t;
#define D(x) ((field_t){&(x), NULL})
#define R(x) ((field_t){NULL, &(x)})

static void header_f64(hv_exec_plan_t *pl, hv_exec_params_t *p, field_t f[HEADER_F64])
{
    field_t list[HEADER_F64] = {R(p->time_scale),
                                R(p->margin),
                                R(p->slack_s),
                                R(p->latency_s),
                                R(p->heartbeat_timeout_s),
                                R(p->heartbeat_period_s),
                                R(p->startup_timeout_s),
                                R(p->command_timeout_s),
                                R(p->home_max_s),
                                R(p->cut_s),
                                R(p->release_s),
                                R(p->vehicle_speed_mps),
                                R(p->vehicle_accel_mps2),
                                R(p->resend_s),
                                R(pl->row_start_m),
                                R(pl->row_length_m),
                                R(pl->stop_margin_m),
                                D(pl->planned_makespan_s),
                                D(pl->planned_pick_s),
                                D(pl->final_drive_s),
                                D(pl->expected_makespan_s),
                                R(pl->home[0][0]),
                                R(pl->home[0][1]),
                                R(pl->home[0][2]),
                                R(pl->home[0][3]),
                                R(pl->home[1][0]),
                                R(pl->home[1][1]),
                                R(pl->home[1][2]),
                                R(pl->home[1][3])};
    memcpy(f, list, sizeof list);
}

static void stop_f64(hv_exec_stop_t *s, field_t f[STOP_F64])
{
    field_t list[STOP_F64] = {R(s->y_m), D(s->arm_s[0]), D(s->arm_s[1]), D(s->expected_s),
                              D(s->drive_s)};
    memcpy(f, list, sizeof list);
}

static void pick_f64(hv_exec_pick_t *k, field_t f[PICK_F64])
{
    field_t list[PICK_F64] = {R(k->q[0]),   R(k->q[1]),    R(k->q[2]),   R(k->q[3]),
                              R(k->move_s), D(k->cycle_s), D(k->cost_s), D(k->start_s),
                              D(k->x_m),    D(k->y_m),     D(k->z_m),    D(k->yaw_rad)};
    memcpy(f, list, sizeof list);
}

static double field_get(field_t f)
{
    return f.d ? *f.d : (double)*f.r;
}

/* Store v; 0 when it is not finite in the field's type (a real too large for a float is
 * refused before the conversion, which C leaves undefined for it). */
static int field_set(field_t f, double v)
{
    if (f.d) {
        *f.d = v;
        return isfinite(v);
    }
    if (!(fabs(v) <= (double)HV_EXEC_REAL_MAX))
        return 0;
    *f.r = (hv_exec_real_t)v;
    return 1;
}

static void put_f64(uint8_t *b, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    for (unsigned i = 0; i < 8; i++)
        b[i] = (uint8_t)((u >> (8u * i)) & 0xFFu);
}

static double get_f64(const uint8_t *b)
{
    uint64_t u = 0;
    double v;
    for (unsigned i = 0; i < 8; i++)
        u |= (uint64_t)b[i] << (8u * i);
    memcpy(&v, &u, sizeof v);
    return v;
}

size_t hv_fw_image_size(unsigned n_stops, unsigned n_picks)
{
    return HV_FW_IMAGE_HEADER + (size_t)n_stops * HV_FW_IMAGE_STOP +
           (size_t)n_picks * HV_FW_IMAGE_PICK;
}

size_t hv_fw_image_write(const hv_exec_plan_t *plan, const hv_exec_params_t *prm, uint8_t *buf,
                         size_t len)
{
    size_t need = hv_fw_image_size(plan->n_stops, plan->n_picks);
    if (len < need)
        return 0;
    /* the field tables point into non-const structs; here they are only read */
    hv_exec_params_t p = *prm;
    hv_exec_plan_t *pl = (hv_exec_plan_t *)(uintptr_t)plan;
    field_t f[HEADER_F64];
    uint8_t *b = buf;
    hv_fw_put_u32(b, HV_FW_IMAGE_MAGIC);
    hv_fw_put_u16(b + 4, HV_FW_IMAGE_VERSION);
    hv_fw_put_u16(b + 6, plan->n_stops);
    hv_fw_put_u16(b + 8, plan->n_picks);
    b[10] = (uint8_t)prm->max_retries;
    b[11] = (uint8_t)prm->clear_estop;
    header_f64(pl, &p, f);
    for (unsigned i = 0; i < HEADER_F64; i++)
        put_f64(b + 12 + 8 * i, field_get(f[i]));
    b += HV_FW_IMAGE_HEADER;
    for (unsigned s = 0; s < plan->n_stops; s++, b += HV_FW_IMAGE_STOP) {
        hv_exec_stop_t *st = &pl->stops[s];
        hv_fw_put_u32(b, st->plan_index);
        hv_fw_put_u16(b + 4, st->first[0]);
        hv_fw_put_u16(b + 6, st->first[1]);
        hv_fw_put_u16(b + 8, st->count[0]);
        hv_fw_put_u16(b + 10, st->count[1]);
        stop_f64(st, f);
        for (unsigned i = 0; i < STOP_F64; i++)
            put_f64(b + 12 + 8 * i, field_get(f[i]));
    }
    for (unsigned k = 0; k < plan->n_picks; k++, b += HV_FW_IMAGE_PICK) {
        hv_exec_pick_t *pk = &pl->picks[k];
        b[0] = (uint8_t)pk->side;
        b[1] = (uint8_t)(pk->reachable ? 1 : 0);
        hv_fw_put_u16(b + 2, pk->stop);
        memset(b + 4, 0, HV_EXEC_ID_LEN);
        for (unsigned i = 0; i + 1 < HV_EXEC_ID_LEN && pk->id[i]; i++)
            b[4 + i] = (uint8_t)pk->id[i];
        pick_f64(pk, f);
        for (unsigned i = 0; i < PICK_F64; i++)
            put_f64(b + 36 + 8 * i, field_get(f[i]));
    }
    return need;
}

void hv_fw_image_begin(hv_fw_image_reader_t *r, hv_exec_plan_t *plan, hv_exec_params_t *prm,
                       uint32_t total, uint32_t crc)
{
    memset(r, 0, sizeof *r);
    r->plan = plan;
    r->prm = prm;
    r->total = total;
    r->crc_want = crc;
    memset(plan, 0, sizeof *plan);
}

/* The n f64 at b into the fields f; 0 when one is not finite in its field's type. */
static int take_f64(const field_t *f, unsigned n, const uint8_t *b)
{
    int ok = 1;
    for (unsigned i = 0; i < n; i++)
        ok &= field_set(f[i], get_f64(b + 8 * i));
    return ok;
}

static hv_status_t take_header(hv_fw_image_reader_t *r)
{
    const uint8_t *b = r->buf;
    hv_exec_plan_t *pl = r->plan;
    field_t f[HEADER_F64];
    if (hv_fw_get_u32(b) != HV_FW_IMAGE_MAGIC || hv_fw_get_u16(b + 4) != HV_FW_IMAGE_VERSION)
        return HV_ERR_FW_UPLOAD_FORMAT;
    unsigned n_stops = hv_fw_get_u16(b + 6), n_picks = hv_fw_get_u16(b + 8);
    if (n_stops == 0 || n_stops > HV_EXEC_MAX_STOPS || n_picks > HV_EXEC_MAX_PICKS ||
        b[10] >= 100 || b[11] > 1)
        return HV_ERR_FW_UPLOAD_FORMAT;
    if (hv_fw_image_size(n_stops, n_picks) != r->total)
        return HV_ERR_FW_UPLOAD_LENGTH;
    pl->n_stops = (uint16_t)n_stops;
    pl->n_picks = (uint16_t)n_picks;
    r->prm->max_retries = b[10];
    r->prm->clear_estop = b[11];
    header_f64(pl, r->prm, f);
    return take_f64(f, HEADER_F64, b + 12) ? HV_OK : HV_ERR_FW_UPLOAD_FORMAT;
}

static hv_status_t take_stop(hv_fw_image_reader_t *r, unsigned s)
{
    const uint8_t *b = r->buf;
    hv_exec_stop_t *st = &r->plan->stops[s];
    field_t f[STOP_F64];
    st->plan_index = hv_fw_get_u32(b);
    for (unsigned a = 0; a < 2; a++) {
        st->first[a] = (uint16_t)hv_fw_get_u16(b + 4 + 2 * a);
        st->count[a] = (uint16_t)hv_fw_get_u16(b + 8 + 2 * a);
        if ((unsigned)st->first[a] + st->count[a] > r->plan->n_picks)
            return HV_ERR_FW_UPLOAD_FORMAT;
    }
    stop_f64(st, f);
    return take_f64(f, STOP_F64, b + 12) ? HV_OK : HV_ERR_FW_UPLOAD_FORMAT;
}

static hv_status_t take_pick(hv_fw_image_reader_t *r, unsigned k)
{
    const uint8_t *b = r->buf;
    hv_exec_pick_t *pk = &r->plan->picks[k];
    field_t f[PICK_F64];
    if (b[0] > 1 || b[1] > 1 || hv_fw_get_u16(b + 2) >= r->plan->n_stops)
        return HV_ERR_FW_UPLOAD_FORMAT;
    const hv_exec_stop_t *st = &r->plan->stops[hv_fw_get_u16(b + 2)];
    /* the pick lies in its stop's range of its arm: the state machine walks those ranges */
    if (k < st->first[b[0]] || k >= (unsigned)st->first[b[0]] + st->count[b[0]])
        return HV_ERR_FW_UPLOAD_FORMAT;
    size_t n = 0;
    while (n < HV_EXEC_ID_LEN && b[4 + n] != 0) {
        if (!hv_fruit_id_char(b[4 + n]))
            return HV_ERR_FW_UPLOAD_FORMAT;
        n++;
    }
    if (n == 0 || n == HV_EXEC_ID_LEN)
        return HV_ERR_FW_UPLOAD_FORMAT;
    memcpy(pk->id, b + 4, n);
    pk->id[n] = '\0';
    pk->side = (hv_side_t)b[0];
    pk->reachable = b[1];
    pk->stop = (uint16_t)hv_fw_get_u16(b + 2);
    pk->ik_status = pk->reachable ? HV_OK : HV_ERR_UNREACHABLE;
    pick_f64(pk, f);
    if (!pk->reachable)
        r->plan->n_unreachable++;
    return take_f64(f, PICK_F64, b + 36) ? HV_OK : HV_ERR_FW_UPLOAD_FORMAT;
}

/* size of record number `i` (header first); 0 past the last */
static unsigned record_size(const hv_fw_image_reader_t *r, unsigned i)
{
    if (i == 0)
        return HV_FW_IMAGE_HEADER;
    if (i <= r->plan->n_stops)
        return HV_FW_IMAGE_STOP;
    if (i <= (unsigned)r->plan->n_stops + r->plan->n_picks)
        return HV_FW_IMAGE_PICK;
    return 0;
}

static hv_status_t take_record(hv_fw_image_reader_t *r)
{
    unsigned i = r->record;
    if (i == 0)
        return take_header(r);
    if (i <= r->plan->n_stops)
        return take_stop(r, i - 1);
    return take_pick(r, i - 1 - r->plan->n_stops);
}

hv_status_t hv_fw_image_data(hv_fw_image_reader_t *r, uint32_t offset, const uint8_t *data,
                             size_t n)
{
    if (offset != r->received)
        return HV_ERR_FW_UPLOAD_ORDER;
    if (n > r->total - r->received)
        n = r->total - r->received; /* the last frame's padding */
    r->crc = hv_crc32(r->crc, data, n);
    r->received += (uint32_t)n;
    for (size_t i = 0; i < n; i++) {
        unsigned size = record_size(r, r->record);
        if (size == 0)
            return HV_ERR_FW_UPLOAD_LENGTH;
        r->buf[r->fill++] = data[i];
        if (r->fill == size) {
            hv_status_t st = take_record(r);
            if (st != HV_OK)
                return st;
            r->record++;
            r->fill = 0;
        }
    }
    return HV_OK;
}

int hv_fw_image_complete(const hv_fw_image_reader_t *r)
{
    return r->received == r->total;
}

hv_status_t hv_fw_image_finish(const hv_fw_image_reader_t *r)
{
    if (!hv_fw_image_complete(r) || record_size(r, r->record) != 0 || r->fill != 0)
        return HV_ERR_FW_UPLOAD_LENGTH;
    return r->crc == r->crc_want ? HV_OK : HV_ERR_FW_UPLOAD_CRC;
}
