/* Fuzz target: the firmware's plan upload (firmware/fw_upload.c, plan_image.c), the DBC's
 * ExecutorPlanBegin / ExecutorPlanData frames in any order, lengths and CRCs, around the
 * image of a real plan (fuzz/data/plan.json, prepared, with the default parameters).
 *
 * Built with the firmware's tables (HV_FW_MAX_STOPS, HV_FW_MAX_PICKS) and its single
 * precision, so capacity and number checks are the firmware's.
 *
 * Input: operations, each an opcode byte and its arguments (until FRAMES_MAX frames were
 * sent); opcode & 7:
 *   0 raw frame   kind (bits 0-1: Begin, Data, Status, else id from the next 2 bytes;
 *                 bits 2-4: flags EXT, RTR, ERR), dlc (1 byte mod 9), data
 *   1 Begin       1 byte: bit 0 the image's size, else 2 bytes of total; bit 1 its CRC,
 *                 else the CRC with the byte's upper bits flipped
 *   2 Data        chunk number (2 bytes): the image's 6 bytes there, at their offset
 *   3 Data        the chunk where the reader stands; 1 byte: bit 7 flips a data bit
 *   4 Data        every chunk from where the reader stands, while it receives
 *   5 the caller  an accepted plan starts (hv_exec_init, as the firmware's start_plan):
 *                 RUNNING, or REFUSED with its error
 *   6 Data        at an offset of 2 bytes, 6 bytes of data from the input
 *   7 the last frame again (a repeat on the bus)
 *
 * Properties after every frame: no crash or undefined behaviour; a frame not taken changes
 * nothing; the state is one of the DBC's and the decoder's errors are its named codes;
 * bytes received never exceed the announced total; an accepted upload received every
 * announced byte with the announced CRC, holds a plan whose stops and picks point inside
 * it, and, when it is the real image, decodes to it exactly (written again, the same
 * bytes); while RUNNING the plan in use is not touched; the status frame says the state,
 * bytes and error. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_plan.h"
#include "fuzz_support.h"
#include "fw_status.h"
#include "fw_upload.h"
#include "harvest_can.h"
#include "hv/cost_table.h" /* hv_crc32 */
#include "hv/exec_status.h"

#define IMAGE_MAX  4096u /* the image of fuzz/data/plan.json: 1984 bytes */
/* frames per input: 3 whole uploads of that image (331 frames each); beyond, an
 * input only repeats what it did */
#define FRAMES_MAX 1024u

typedef struct upload_run {
    hv_fw_upload_t u;
    hv_exec_plan_t plan;
    hv_exec_params_t prm;
    hv_exec_sm_t sm;
    hv_can_frame_t last;
    int begun;       /* a Begin was taken */
    unsigned frames; /* frames of this input so far */
    uint8_t running_image[IMAGE_MAX];
    size_t running_len;
} upload_run_t;

typedef struct image {
    uint8_t b[IMAGE_MAX];
    size_t len;
    uint32_t crc;
} image_t;

static const image_t *real_image(void)
{
    static image_t img; /* built once (fuzz_support.h) */
    if (img.len == 0) {
        hv_exec_params_t prm;
        hv_exec_params_default(&prm);
        prm.home_max_s = 20.0;
        img.len = hv_fw_image_write(hv_fuzz_plan(1), &prm, img.b, sizeof img.b);
        if (img.len == 0)
            hv_fuzz_fail("the image of fuzz/data/plan.json does not fit %u bytes", IMAGE_MAX);
        img.crc = hv_crc32(0, img.b, img.len);
    }
    return &img;
}

static int upload_error(hv_status_t st)
{
    return st == HV_OK || st == HV_ERR_FW_UPLOAD_ORDER || st == HV_ERR_FW_UPLOAD_LENGTH ||
           st == HV_ERR_FW_UPLOAD_FORMAT || st == HV_ERR_FW_UPLOAD_CRC ||
           st == HV_ERR_FW_UPLOAD_BUSY || st == HV_ERR_FW_UPLOAD_TRUNCATED;
}

/* the accepted plan's stops and picks point inside it */
static void check_plan(const hv_exec_plan_t *p)
{
    if (p->n_stops == 0 || p->n_stops > HV_EXEC_MAX_STOPS || p->n_picks > HV_EXEC_MAX_PICKS)
        hv_fuzz_fail("accepted plan of %u stops, %u picks", p->n_stops, p->n_picks);
    for (unsigned s = 0; s < p->n_stops; s++)
        for (unsigned a = 0; a < 2; a++)
            if ((unsigned)p->stops[s].first[a] + p->stops[s].count[a] > p->n_picks)
                hv_fuzz_fail("accepted stop %u: arm %u's picks beyond the plan", s, a);
    for (unsigned k = 0; k < p->n_picks; k++) {
        const hv_exec_pick_t *pk = &p->picks[k];
        const hv_exec_stop_t *st = &p->stops[pk->stop];
        if (pk->stop >= p->n_stops || (unsigned)pk->side > 1 || k < st->first[pk->side] ||
            k >= (unsigned)st->first[pk->side] + st->count[pk->side])
            hv_fuzz_fail("accepted pick %u outside its stop's range", k);
    }
}

static void check_status(const hv_fw_upload_t *u)
{
    hv_can_frame_t f;
    struct harvest_can_executor_plan_status_t m;
    hv_fw_upload_status(u, &f);
    if (f.id != HARVEST_CAN_EXECUTOR_PLAN_STATUS_FRAME_ID ||
        harvest_can_executor_plan_status_unpack(&m, f.data, f.dlc) != 0 || m.state != u->state ||
        m.bytes_received != (uint16_t)u->rd.received || m.error != u->error)
        hv_fuzz_fail("the status frame does not say state %d, %u bytes, error %d", (int)u->state,
                     (unsigned)u->rd.received, (int)u->error);
}

static void frame(upload_run_t *U, const hv_can_frame_t *f)
{
    static hv_fw_upload_t before; /* large: off the fuzzer's stack */
    before = U->u;
    U->last = *f;
    U->frames++;
    int answer = -1;
    int taken = hv_fw_upload_frame(&U->u, f, &U->plan, &U->prm, &answer);
    const hv_fw_upload_t *u = &U->u;
    if (taken != 0 && taken != 1)
        hv_fuzz_fail("upload_frame returned %d", taken);
    if (!taken && (answer != 0 || memcmp(&before, u, sizeof before) != 0))
        hv_fuzz_fail("a frame not taken (id %x) changed the upload", (unsigned)f->id);
    if (answer != 0 && answer != 1)
        hv_fuzz_fail("answer %d", answer);
    U->begun |= u->state != before.state && u->state == HV_UPLOAD_RECEIVING;
    if (u->state != HV_UPLOAD_IDLE && u->state != HV_UPLOAD_RECEIVING &&
        u->state != HV_UPLOAD_ACCEPTED && u->state != HV_UPLOAD_REFUSED &&
        u->state != HV_UPLOAD_RUNNING)
        hv_fuzz_fail("state %d", (int)u->state);
    if (u->error != before.error && !upload_error(u->error))
        hv_fuzz_fail("error %s is none of the upload's", hv_fw_status_name(u->error));
    if ((u->state != before.state || u->error != before.error) && !answer)
        hv_fuzz_fail("state or error changed without an answer");
    if (U->begun && u->rd.received > u->rd.total)
        hv_fuzz_fail("%u bytes received of %u announced", (unsigned)u->rd.received,
                     (unsigned)u->rd.total);
    if (u->state == HV_UPLOAD_ACCEPTED && before.state != HV_UPLOAD_ACCEPTED) {
        if (!hv_fw_image_complete(&u->rd) || u->rd.crc != u->rd.crc_want ||
            hv_fw_image_finish(&u->rd) != HV_OK || u->error != HV_OK)
            hv_fuzz_fail("accepted: %u of %u bytes, CRC %08x of %08x", (unsigned)u->rd.received,
                         (unsigned)u->rd.total, (unsigned)u->rd.crc, (unsigned)u->rd.crc_want);
        check_plan(&U->plan);
        const image_t *img = real_image();
        static uint8_t again[IMAGE_MAX];
        if (u->rd.total == img->len && u->rd.crc_want == img->crc &&
            (hv_fw_image_write(&U->plan, &U->prm, again, sizeof again) != img->len ||
             memcmp(again, img->b, img->len) != 0))
            hv_fuzz_fail("the real image accepted decodes to another plan");
    }
    if (u->state == HV_UPLOAD_RUNNING) {
        static uint8_t now[IMAGE_MAX];
        size_t n = hv_fw_image_write(&U->plan, &U->prm, now, sizeof now);
        if (n != U->running_len || memcmp(now, U->running_image, n) != 0)
            hv_fuzz_fail("the plan in use changed while RUNNING");
    }
    check_status(u);
}

static void send(upload_run_t *U, uint32_t id, const uint8_t *data, int len)
{
    if (len < 0)
        hv_fuzz_fail("pack failed for id %x", (unsigned)id);
    hv_can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = id;
    f.dlc = (uint8_t)len;
    memcpy(f.data, data, (size_t)len);
    frame(U, &f);
}

static void begin(upload_run_t *U, uint32_t total, uint32_t crc)
{
    struct harvest_can_executor_plan_begin_t m = {total, crc};
    uint8_t b[8];
    send(U, HARVEST_CAN_EXECUTOR_PLAN_BEGIN_FRAME_ID, b,
         harvest_can_executor_plan_begin_pack(b, &m, sizeof b));
}

/* 6 bytes at offset (zeros past the end, as the host pads the last frame) */
static void data6(upload_run_t *U, uint32_t offset, const uint8_t *bytes, size_t n)
{
    struct harvest_can_executor_plan_data_t m;
    uint8_t b[8];
    m.offset = (uint16_t)offset;
    m.data = 0;
    for (size_t i = 0; i < 6 && i < n; i++)
        m.data |= (uint64_t)bytes[i] << (8u * i);
    send(U, HARVEST_CAN_EXECUTOR_PLAN_DATA_FRAME_ID, b,
         harvest_can_executor_plan_data_pack(b, &m, sizeof b));
}

static void chunk(upload_run_t *U, uint32_t offset, uint8_t flip)
{
    const image_t *img = real_image();
    uint8_t six[6] = {0};
    for (uint32_t i = 0; i < 6 && offset + i < img->len; i++)
        six[i] = img->b[offset + i];
    if (flip & 0x80)
        six[(flip & 7) % 6] ^= (uint8_t)(1u << ((flip >> 3) & 7));
    data6(U, offset, six, 6);
}

static uint16_t u16(hv_fuzz_reader_t *r)
{
    return (uint16_t)(hv_fuzz_byte(r) | (hv_fuzz_byte(r) << 8));
}

/* the firmware's start_plan without the journal: the state machine takes the plan or not */
static void start(upload_run_t *U)
{
    if (U->u.state != HV_UPLOAD_ACCEPTED)
        return;
    hv_status_t st = hv_exec_init(&U->sm, &U->plan, &U->prm, NULL);
    if (st != HV_OK) {
        U->u.state = HV_UPLOAD_REFUSED;
        U->u.error = st;
        return;
    }
    U->u.state = HV_UPLOAD_RUNNING;
    U->running_len = hv_fw_image_write(&U->plan, &U->prm, U->running_image, IMAGE_MAX);
    if (U->running_len == 0)
        hv_fuzz_fail("a running plan of %u stops, %u picks has no image", U->plan.n_stops,
                     U->plan.n_picks);
}

static void raw(upload_run_t *U, hv_fuzz_reader_t *r)
{
    static const uint32_t ids[3] = {HARVEST_CAN_EXECUTOR_PLAN_BEGIN_FRAME_ID,
                                    HARVEST_CAN_EXECUTOR_PLAN_DATA_FRAME_ID,
                                    HARVEST_CAN_EXECUTOR_PLAN_STATUS_FRAME_ID};
    uint8_t kind = hv_fuzz_byte(r);
    hv_can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = (kind & 3) < 3 ? ids[kind & 3] : (uint32_t)u16(r) & HV_CAN_SFF_MASK;
    f.flags = (uint8_t)((kind >> 2) & 7);
    f.dlc = hv_fuzz_byte(r) % 9;
    for (unsigned k = 0; k < f.dlc; k++)
        f.data[k] = hv_fuzz_byte(r);
    frame(U, &f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static upload_run_t U; /* large: off the fuzzer's stack */
    const image_t *img = real_image();
    hv_fuzz_reader_t r = {data, size};
    memset(&U, 0, sizeof U);
    U.u.state = HV_UPLOAD_IDLE;
    int op;
    unsigned ops = 0;
    while ((op = hv_fuzz_next(&r)) >= 0 && ops++ < 4096 && U.frames < FRAMES_MAX) {
        switch (op & 7) {
        case 0: raw(&U, &r); break;
        case 1: {
            uint8_t b = hv_fuzz_byte(&r);
            uint32_t total = (b & 1) ? (uint32_t)img->len : u16(&r);
            begin(&U, total, (b & 2) ? img->crc : img->crc ^ ((uint32_t)b << 24));
            break;
        }
        case 2: chunk(&U, 6u * u16(&r), 0); break;
        case 3: chunk(&U, U.u.rd.received, hv_fuzz_byte(&r)); break;
        case 4:
            while (U.u.state == HV_UPLOAD_RECEIVING && U.u.rd.received < U.u.rd.total)
                chunk(&U, U.u.rd.received, 0);
            break;
        case 5: start(&U); break;
        case 6: {
            uint16_t offset = u16(&r);
            uint8_t six[6];
            for (unsigned i = 0; i < 6; i++)
                six[i] = hv_fuzz_byte(&r);
            data6(&U, offset, six, 6);
            break;
        }
        case 7: {
            hv_can_frame_t f = U.last;
            frame(&U, &f);
            break;
        }
        }
    }
    if (getenv("HV_FUZZ_TRACE"))
        fprintf(stderr, "fuzz_plan_upload: %u ops, state %d, %u of %u bytes, %s\n", ops,
                (int)U.u.state, (unsigned)U.u.rd.received, (unsigned)U.u.rd.total,
                hv_fw_status_name(U.u.error));
    return 0;
}
