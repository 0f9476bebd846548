/* hv-can-tool: the CAN layer from the command line (send, receive, echo, ping, flood,
 * sink, pack, unpack). The pytest suites (tests/can) and the benchmark (bench/can) drive
 * it against python-can; it is also handy on a real bus. Run with --help. */
#define _GNU_SOURCE /* SO_RCVBUFFORCE */
#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>

#include "hv/can_bus.h"
#include "hv/can_messages.h"
#include "hv/cli.h"
#include "hv/version.h"

static const char k_prog[] = "hv-can-tool";

static const char usage[] =
    "usage: hv-can-tool [--bus SPEC] COMMAND [options]\n"
    "\n"
    "Send and receive CAN frames through the harvest CAN layer (executor/can).\n"
    "SPEC is socketcan:IFNAME (e.g. socketcan:vcan0) or udp[:GROUP[:PORT[:IFADDR]]]\n"
    "(python-can udp_multicast wire format; default udp:239.74.163.2:43113:127.0.0.1).\n"
    "Frames are written ID#HEX: 3 hex digits = standard id, 8 = extended, ID#R<dlc> for a\n"
    "remote frame; received error frames print as ERR <class>#HEX.\n"
    "\n"
    "commands:\n"
    "  send [FRAME...]   send the frames given, or one per stdin line when none\n"
    "  send-msg          read 'Name Sig=value ...' lines from stdin, pack each with the\n"
    "                    cantools-generated code and send it\n"
    "  recv              print received frames, one per line\n"
    "  echo              send every received frame back with id + --offset\n"
    "  ping              send --count frames (32-bit sequence in bytes 0..3) to --id and\n"
    "                    wait for each echo on --reply-id; prints round-trip statistics\n"
    "  flood             send --count frames on --id carrying a 32-bit counter, as fast as\n"
    "                    the bus accepts them\n"
    "  sink              receive a flood on --id and check that no frame is lost or reordered\n"
    "  pack              (no bus) read 'Name Sig=value ...' lines, print ID#HEX per line\n"
    "  unpack            (no bus) read ID#HEX lines, print 'Name Sig=value ...' per line\n"
    "  list              (no bus) print every DBC message: id, length, name, signals\n"
    "\n"
    "options:\n"
    "  --count N         frames to receive/echo/send (recv/echo: 0 = until idle timeout)\n"
    "  --timeout-ms T    give up after T ms without a frame (default 2000; -1 = never)\n"
    "  --filter ID:MASK  receive filter (hex), may repeat (recv, echo, sink)\n"
    "  --id ID           frame id (hex) for ping/flood/sink (default 7F0 / 7F0 / 7F0)\n"
    "  --reply-id ID     id the echo comes back on for ping (default 7F1)\n"
    "  --offset K        id offset added by echo (default 1)\n"
    "  --window W        ping: frames in flight at once (default 1: pure latency)\n"
    "  --rcvbuf BYTES    enlarge the receive socket buffer (forced when root)\n"
    "  --quiet           recv: count frames but do not print them\n"
    "  --help            this text\n"
    "  --version         the version and exit\n"
    "\n"
    "Readiness: once the bus is open, 'ready <bus name>' is printed on stderr; a summary\n"
    "line 'stats tx=.. rx=.. ...' follows on stderr when the command ends.\n"
    "\n" HV_EXIT_CODES_HELP ",\n"
    "3 timeout or frames lost)\n";

typedef struct opts {
    const char *bus_spec;
    const char *command;
    char **args;
    int n_args;
    long count;
    int timeout_ms;
    hv_can_filter_t filters[HV_CAN_MAX_FILTERS];
    size_t n_filters;
    uint32_t id, reply_id, offset;
    long window;
    long rcvbuf;
    int quiet;
} opts_t;

static int parse_hex_u32(const char *s, uint32_t *out)
{
    char *end;
    errno = 0;
    unsigned long v = strtoul(s, &end, 16);
    if (errno || end == s || *end || v > 0xFFFFFFFFul)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

static int parse_long(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end)
        return -1;
    *out = v;
    return 0;
}

/* The filter ID:MASK (hex) into the next free filter. */
static int parse_filter(const char *v, opts_t *o)
{
    char buf[32];
    if (o->n_filters == HV_CAN_MAX_FILTERS || strlen(v) >= sizeof buf)
        return -1;
    strcpy(buf, v);
    char *colon = strchr(buf, ':');
    if (!colon)
        return -1;
    *colon = '\0';
    hv_can_filter_t *f = &o->filters[o->n_filters];
    if (parse_hex_u32(buf, &f->id) || parse_hex_u32(colon + 1, &f->mask))
        return -1;
    f->ext = (strlen(buf) > 3 || f->id > HV_CAN_SFF_MASK) ? 1 : 0;
    o->n_filters++;
    return 0;
}

enum {
    OPT_BUS = 256,
    OPT_COUNT,
    OPT_TIMEOUT,
    OPT_WINDOW,
    OPT_RCVBUF,
    OPT_ID,
    OPT_REPLY_ID,
    OPT_OFFSET,
    OPT_FILTER,
    OPT_QUIET
};

/* One option's value into `o`; -1 when it is out of range or malformed. */
static int apply_option(int opt, const char *v, opts_t *o)
{
    long n;
    switch (opt) {
    case OPT_BUS: o->bus_spec = v; return 0;
    case OPT_QUIET: o->quiet = 1; return 0;
    case OPT_COUNT: return (parse_long(v, &o->count) || o->count < 0) ? -1 : 0;
    case OPT_TIMEOUT:
        if (parse_long(v, &n) || n < -1 || n > 86400000)
            return -1;
        o->timeout_ms = (int)n;
        return 0;
    case OPT_WINDOW:
        return (parse_long(v, &o->window) || o->window < 1 || o->window > 1024) ? -1 : 0;
    case OPT_RCVBUF:
        return (parse_long(v, &o->rcvbuf) || o->rcvbuf < 0 || o->rcvbuf > (1l << 30)) ? -1 : 0;
    case OPT_ID: return (parse_hex_u32(v, &o->id) || o->id > HV_CAN_SFF_MASK) ? -1 : 0;
    case OPT_REPLY_ID:
        return (parse_hex_u32(v, &o->reply_id) || o->reply_id > HV_CAN_SFF_MASK) ? -1 : 0;
    case OPT_OFFSET: return (parse_hex_u32(v, &o->offset) || o->offset > HV_CAN_SFF_MASK) ? -1 : 0;
    case OPT_FILTER: return parse_filter(v, o);
    default: return -1;
    }
}

/* getopt_long: options anywhere (--opt value or --opt=value), then COMMAND and its frames. */
static int parse_args(int argc, char **argv, opts_t *o)
{
    static const struct option longopts[] = {
        {"bus", required_argument, NULL, OPT_BUS},
        {"count", required_argument, NULL, OPT_COUNT},
        {"timeout-ms", required_argument, NULL, OPT_TIMEOUT},
        {"window", required_argument, NULL, OPT_WINDOW},
        {"rcvbuf", required_argument, NULL, OPT_RCVBUF},
        {"id", required_argument, NULL, OPT_ID},
        {"reply-id", required_argument, NULL, OPT_REPLY_ID},
        {"offset", required_argument, NULL, OPT_OFFSET},
        {"filter", required_argument, NULL, OPT_FILTER},
        {"quiet", no_argument, NULL, OPT_QUIET},
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    memset(o, 0, sizeof *o);
    o->bus_spec = "udp";
    o->timeout_ms = 2000;
    o->id = 0x7F0;
    o->reply_id = 0x7F1;
    o->offset = 1;
    o->window = 1;
    opterr = 0; /* our own messages, naming the option */
    int opt, idx = -1;
    while ((opt = getopt_long(argc, argv, ":h", longopts, &idx)) != -1) {
        if (opt == 'h') {
            fputs(usage, stdout);
            exit(0);
        }
        if (opt == 'V') {
            printf("hv-can-tool %s\n", HV_VERSION);
            exit(0);
        }
        if (opt == '?' || opt == ':') {
            hv_cli_option_error(k_prog, opt, optopt, argv[optind - 1]);
            return -1;
        }
        if (apply_option(opt, optarg, o)) {
            fprintf(stderr, "hv-can-tool: --%s: bad value '%s'\n", longopts[idx].name, optarg);
            return -1;
        }
    }
    if (optind >= argc) {
        hv_cli_usage_error(k_prog, "COMMAND", "missing");
        return -1;
    }
    o->command = argv[optind];
    o->args = argv + optind + 1;
    o->n_args = argc - optind - 1;
    return 0;
}

/* ---- frame text ---------------------------------------------------------------- */

static int hexval(int c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* "123#0102..", "12345678#..", "123#R4" -> frame; -1 with a message on bad text. */
static int parse_frame(const char *text, hv_can_frame_t *f)
{
    memset(f, 0, sizeof *f);
    const char *hash = strchr(text, '#');
    size_t id_len = hash ? (size_t)(hash - text) : 0;
    if (!hash || (id_len != 3 && id_len != 8)) {
        fprintf(stderr, "hv-can-tool: frame '%s': expected ID#HEX with a 3 or 8 digit id\n", text);
        return -1;
    }
    for (size_t i = 0; i < id_len; i++) {
        int h = hexval(text[i]);
        if (h < 0) {
            fprintf(stderr, "hv-can-tool: frame '%s': id is not hex\n", text);
            return -1;
        }
        f->id = (f->id << 4) | (uint32_t)h;
    }
    if (id_len == 8)
        f->flags |= HV_CAN_FLAG_EXT;
    if (f->id > (id_len == 8 ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK)) {
        fprintf(stderr, "hv-can-tool: frame '%s': id out of range\n", text);
        return -1;
    }
    const char *d = hash + 1;
    if (*d == 'R') {
        f->flags |= HV_CAN_FLAG_RTR;
        f->dlc = (uint8_t)(d[1] ? hexval(d[1]) : 0);
        if (f->dlc > 8 || (d[1] && d[2])) {
            fprintf(stderr, "hv-can-tool: frame '%s': bad remote length\n", text);
            return -1;
        }
        return 0;
    }
    size_t n = strlen(d);
    if (n % 2 || n > 16) {
        fprintf(stderr, "hv-can-tool: frame '%s': data must be 0..8 bytes of hex pairs\n", text);
        return -1;
    }
    for (size_t i = 0; i < n / 2; i++) {
        int hi = hexval(d[2 * i]), lo = hexval(d[2 * i + 1]);
        if (hi < 0 || lo < 0) {
            fprintf(stderr, "hv-can-tool: frame '%s': data is not hex\n", text);
            return -1;
        }
        f->data[i] = (uint8_t)(hi << 4 | lo);
    }
    f->dlc = (uint8_t)(n / 2);
    return 0;
}

static void print_frame(FILE *out, const hv_can_frame_t *f)
{
    if (f->flags & HV_CAN_FLAG_ERR)
        fputs("ERR ", out);
    if (f->flags & HV_CAN_FLAG_EXT)
        fprintf(out, "%08" PRIX32 "#", f->id);
    else
        fprintf(out, "%03" PRIX32 "#", f->id);
    if (f->flags & HV_CAN_FLAG_RTR) {
        fprintf(out, "R%u\n", f->dlc);
        return;
    }
    for (unsigned i = 0; i < f->dlc; i++)
        fprintf(out, "%02X", f->data[i]);
    fputc('\n', out);
}

/* "Name Sig=v Sig=v ..." -> packed frame through the generated code. */
static int pack_line(char *line, hv_can_frame_t *f)
{
    char *save = NULL;
    char *name = strtok_r(line, " \t\r\n", &save);
    if (!name)
        return 1; /* blank line: nothing to do */
    const hv_can_message_desc_t *m = hv_can_message_by_name(name);
    if (!m) {
        fprintf(stderr, "hv-can-tool: no message '%s' in harvest.dbc (see list)\n", name);
        return -1;
    }
    double values[HV_CAN_MAX_SIGNALS];
    int seen[HV_CAN_MAX_SIGNALS] = {0};
    char *tok;
    while ((tok = strtok_r(NULL, " \t\r\n", &save))) {
        char *eq = strchr(tok, '=');
        size_t k;
        if (!eq) {
            fprintf(stderr, "hv-can-tool: %s: '%s' is not Signal=value\n", name, tok);
            return -1;
        }
        *eq = '\0';
        for (k = 0; k < m->n_signals && strcmp(m->signals[k], tok); k++) {
        }
        if (k == m->n_signals) {
            fprintf(stderr, "hv-can-tool: %s: no signal '%s'\n", name, tok);
            return -1;
        }
        char *end;
        errno = 0;
        values[k] = strtod(eq + 1, &end);
        if (errno || end == eq + 1 || *end) {
            fprintf(stderr, "hv-can-tool: %s.%s: '%s' is not a number\n", name, tok, eq + 1);
            return -1;
        }
        if (values[k] < m->minimum[k] || values[k] > m->maximum[k]) {
            fprintf(stderr, "hv-can-tool: %s.%s=%s outside the DBC range [%.17g, %.17g]\n", name,
                    tok, eq + 1, m->minimum[k], m->maximum[k]);
            return -1;
        }
        seen[k] = 1;
    }
    for (size_t k = 0; k < m->n_signals; k++) {
        if (!seen[k]) {
            fprintf(stderr, "hv-can-tool: %s: signal '%s' missing\n", name, m->signals[k]);
            return -1;
        }
    }
    memset(f, 0, sizeof *f);
    f->id = m->id;
    f->dlc = m->length;
    if (m->pack(f->data, values) != (int)m->length) {
        fprintf(stderr, "hv-can-tool: %s: pack failed\n", name);
        return -1;
    }
    return 0;
}

static void print_unpacked(FILE *out, const hv_can_frame_t *f)
{
    const hv_can_message_desc_t *m = hv_can_message_by_id(f->id);
    double values[HV_CAN_MAX_SIGNALS];
    if (!m || (f->flags & (HV_CAN_FLAG_EXT | HV_CAN_FLAG_RTR | HV_CAN_FLAG_ERR))) {
        fprintf(out, "? not in harvest.dbc\n");
        return;
    }
    if (m->unpack(f->data, f->dlc, values) < 0) {
        fprintf(out, "? %s: %u bytes, DBC says %u\n", m->name, f->dlc, m->length);
        return;
    }
    fputs(m->name, out);
    for (size_t k = 0; k < m->n_signals; k++)
        fprintf(out, " %s=%.17g", m->signals[k], values[k]);
    fputc('\n', out);
}

/* ---- commands ------------------------------------------------------------------ */

static int cmd_list(void)
{
    for (size_t i = 0; i < hv_can_n_messages; i++) {
        const hv_can_message_desc_t *m = &hv_can_messages[i];
        printf("%03" PRIX32 " %u %s", m->id, m->length, m->name);
        for (size_t k = 0; k < m->n_signals; k++)
            printf(" %s", m->signals[k]);
        putchar('\n');
    }
    return 0;
}

static int cmd_pack(void)
{
    char line[1024];
    int lineno = 0;
    while (fgets(line, sizeof line, stdin)) {
        lineno++;
        hv_can_frame_t f;
        int r = pack_line(line, &f);
        if (r < 0) {
            fprintf(stderr, "hv-can-tool: stdin line %d rejected\n", lineno);
            return HV_EXIT_USAGE;
        }
        if (r == 0)
            print_frame(stdout, &f);
    }
    return 0;
}

static int cmd_unpack(void)
{
    char line[256];
    int lineno = 0;
    while (fgets(line, sizeof line, stdin)) {
        lineno++;
        line[strcspn(line, " \t\r\n")] = '\0';
        if (!line[0])
            continue;
        hv_can_frame_t f;
        if (parse_frame(line, &f)) {
            fprintf(stderr, "hv-can-tool: stdin line %d rejected\n", lineno);
            return HV_EXIT_USAGE;
        }
        print_unpacked(stdout, &f);
    }
    return 0;
}

/* 0, or the exit code: a bad --bus is usage, a bus that does not open a failure. */
static int open_bus(const opts_t *o, hv_can_bus_t *bus)
{
    char spec[128];
    hv_status_t st;
    if (strlen(o->bus_spec) >= sizeof spec) {
        fprintf(stderr, "hv-can-tool: --bus %s: too long\n", o->bus_spec);
        return HV_EXIT_USAGE;
    }
    strcpy(spec, o->bus_spec);
    if (!strncmp(spec, "socketcan:", 10)) {
        st = hv_can_socketcan_open(bus, spec + 10, o->filters, o->n_filters);
    } else if (!strcmp(spec, "udp") || !strncmp(spec, "udp:", 4)) {
        char *group = NULL, *port_s = NULL, *ifaddr = NULL, *save = NULL;
        strtok_r(spec, ":", &save);
        group = strtok_r(NULL, ":", &save);
        port_s = strtok_r(NULL, ":", &save);
        ifaddr = strtok_r(NULL, ":", &save);
        long port = 0;
        if (port_s && (parse_long(port_s, &port) || port < 1 || port > 65535)) {
            fprintf(stderr, "hv-can-tool: --bus %s: bad port '%s'\n", o->bus_spec, port_s);
            return HV_EXIT_USAGE;
        }
        st = hv_can_udp_open(bus, group, (uint16_t)port, ifaddr, o->filters, o->n_filters);
    } else {
        fprintf(stderr, "hv-can-tool: --bus %s: expected socketcan:IFNAME or udp[:...]\n",
                o->bus_spec);
        return HV_EXIT_USAGE;
    }
    if (st != HV_OK) {
        fprintf(stderr, "hv-can-tool: %s: cannot open: %s (%s)\n", o->bus_spec,
                hv_can_status_name(st), strerror(hv_can_last_errno(bus)));
        return HV_EXIT_FAILURE;
    }
    if (o->rcvbuf > 0) {
        int size = (int)o->rcvbuf;
        /* FORCE bypasses rmem_max when we are root (the guest); else best effort */
        if (setsockopt(hv_can_fd(bus), SOL_SOCKET, SO_RCVBUFFORCE, &size, sizeof size) < 0)
            setsockopt(hv_can_fd(bus), SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
    }
    fprintf(stderr, "ready %s\n", hv_can_name(bus));
    fflush(stderr);
    return 0;
}

static void print_stats(const hv_can_bus_t *bus)
{
    hv_can_stats_t s;
    hv_can_get_stats(bus, &s);
    fprintf(stderr,
            "stats tx=%" PRIu64 " rx=%" PRIu64 " error_frames=%" PRIu64 " malformed=%" PRIu64
            " unsupported=%" PRIu64 " filtered=%" PRIu64 " kernel_drops=%" PRIu64
            " tx_failures=%" PRIu64 "\n",
            s.tx_frames, s.rx_frames, s.rx_error_frames, s.rx_malformed, s.rx_unsupported,
            s.rx_filtered, s.rx_kernel_drops, s.tx_failures);
}

static int send_checked(hv_can_bus_t *bus, const hv_can_frame_t *f, int timeout_ms)
{
    hv_status_t st = hv_can_send(bus, f, timeout_ms);
    if (st != HV_OK) {
        fprintf(stderr, "hv-can-tool: send on %s failed: %s (%s)\n", hv_can_name(bus),
                hv_can_status_name(st), strerror(hv_can_last_errno(bus)));
        return -1;
    }
    return 0;
}

static int cmd_send(const opts_t *o, hv_can_bus_t *bus, int packed)
{
    hv_can_frame_t f;
    if (!packed && o->n_args > 0) {
        for (int i = 0; i < o->n_args; i++) {
            if (parse_frame(o->args[i], &f))
                return HV_EXIT_USAGE;
            if (send_checked(bus, &f, o->timeout_ms))
                return HV_EXIT_FAILURE;
        }
        return 0;
    }
    char line[1024];
    int lineno = 0;
    while (fgets(line, sizeof line, stdin)) {
        lineno++;
        int r;
        if (packed) {
            r = pack_line(line, &f);
        } else {
            line[strcspn(line, " \t\r\n")] = '\0';
            r = line[0] ? parse_frame(line, &f) : 1;
        }
        if (r < 0) {
            fprintf(stderr, "hv-can-tool: stdin line %d rejected\n", lineno);
            return HV_EXIT_USAGE;
        }
        if (r == 0 && send_checked(bus, &f, o->timeout_ms))
            return HV_EXIT_FAILURE;
    }
    return 0;
}

/* recv (echo == 0) and echo (echo == 1) */
static int cmd_recv(const opts_t *o, hv_can_bus_t *bus, int echo)
{
    long got = 0;
    while (o->count == 0 || got < o->count) {
        hv_can_frame_t f;
        hv_status_t st = hv_can_recv(bus, &f, o->timeout_ms);
        if (st == (hv_status_t)HV_CAN_ERR_TIMEOUT)
            return (o->count == 0) ? 0 : HV_EXIT_CAN_TIMEOUT;
        if (st != HV_OK) {
            fprintf(stderr, "hv-can-tool: receive failed: %s\n", hv_can_status_name(st));
            return HV_EXIT_FAILURE;
        }
        got++;
        if (echo) {
            if (f.flags & HV_CAN_FLAG_ERR)
                continue;
            f.id = (f.id + o->offset) &
                   ((f.flags & HV_CAN_FLAG_EXT) ? HV_CAN_EFF_MASK : HV_CAN_SFF_MASK);
            if (send_checked(bus, &f, o->timeout_ms))
                return HV_EXIT_FAILURE;
        } else if (!o->quiet) {
            print_frame(stdout, &f);
            fflush(stdout);
        }
    }
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void put_u32(uint8_t *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int cmd_ping(const opts_t *o, hv_can_bus_t *bus)
{
    long n = o->count ? o->count : 1000;
    double *sent_at = calloc((size_t)n, sizeof *sent_at);
    double *rtt = calloc((size_t)n, sizeof *rtt);
    if (!sent_at || !rtt) {
        free(sent_at);
        free(rtt);
        fprintf(stderr, "hv-can-tool: out of memory for %ld samples\n", n);
        return HV_EXIT_FAILURE;
    }
    long next = 0, done = 0, lost = 0, in_flight = 0;
    int rc = 0;
    double t0 = now_s();
    while (done + lost < n) {
        while (next < n && in_flight < o->window) {
            hv_can_frame_t f = {o->id, 8, 0, {0}, 0};
            put_u32(f.data, (uint32_t)next);
            put_u32(f.data + 4, 0xC0FFEEu);
            sent_at[next] = now_s();
            if (send_checked(bus, &f, o->timeout_ms)) {
                rc = HV_EXIT_FAILURE;
                goto out;
            }
            next++;
            in_flight++;
        }
        hv_can_frame_t r;
        hv_status_t st = hv_can_recv(bus, &r, o->timeout_ms);
        if (st == (hv_status_t)HV_CAN_ERR_TIMEOUT) {
            lost += in_flight; /* nothing came back in time: give those up */
            in_flight = 0;
            continue;
        }
        if (st != HV_OK) {
            rc = HV_EXIT_FAILURE;
            goto out;
        }
        if (r.id != o->reply_id || r.dlc != 8 || r.flags != 0)
            continue;
        uint32_t seq = get_u32(r.data);
        if (seq >= (uint32_t)next || sent_at[seq] == 0.0)
            continue; /* stale or duplicate */
        rtt[done++] = now_s() - sent_at[seq];
        sent_at[seq] = 0.0;
        in_flight--;
    }
out:;
    double elapsed = now_s() - t0;
    if (done > 0) {
        qsort(rtt, (size_t)done, sizeof *rtt, cmp_double);
        long p99 = (long)((double)(done - 1) * 0.99 + 0.5);
        printf("ping frames=%ld lost=%ld window=%ld seconds=%.3f fps=%.0f rtt_median_us=%.1f "
               "rtt_p99_us=%.1f rtt_max_us=%.1f\n",
               done, lost, o->window, elapsed, (double)done / elapsed, rtt[(done - 1) / 2] * 1e6,
               rtt[p99] * 1e6, rtt[done - 1] * 1e6);
    } else {
        printf("ping frames=0 lost=%ld\n", lost);
    }
    free(sent_at);
    free(rtt);
    if (rc == 0 && lost > 0)
        rc = HV_EXIT_CAN_TIMEOUT;
    return rc;
}

static int cmd_flood(const opts_t *o, hv_can_bus_t *bus)
{
    long n = o->count ? o->count : 100000;
    double t0 = now_s();
    for (long i = 0; i < n; i++) {
        hv_can_frame_t f = {o->id, 8, 0, {0}, 0};
        put_u32(f.data, (uint32_t)i);
        put_u32(f.data + 4, ~(uint32_t)i);
        if (send_checked(bus, &f, o->timeout_ms))
            return HV_EXIT_FAILURE;
    }
    double elapsed = now_s() - t0;
    printf("flood sent=%ld seconds=%.3f fps=%.0f\n", n, elapsed,
           elapsed > 0 ? (double)n / elapsed : 0.0);
    return 0;
}

static int cmd_sink(const opts_t *o, hv_can_bus_t *bus)
{
    long n = o->count ? o->count : 100000;
    long got = 0, bad = 0, gaps = 0;
    uint32_t expect = 0;
    double t0 = 0.0;
    while (got < n) {
        hv_can_frame_t f;
        hv_status_t st = hv_can_recv(bus, &f, o->timeout_ms);
        if (st == (hv_status_t)HV_CAN_ERR_TIMEOUT)
            break;
        if (st != HV_OK) {
            fprintf(stderr, "hv-can-tool: receive failed: %s\n", hv_can_status_name(st));
            return HV_EXIT_FAILURE;
        }
        if (f.id != o->id || f.dlc != 8 || f.flags)
            continue;
        if (got == 0)
            t0 = now_s();
        uint32_t seq = get_u32(f.data);
        if (get_u32(f.data + 4) != ~seq)
            bad++;
        if (seq != expect)
            gaps++; /* lost, duplicated or reordered frames */
        expect = seq + 1;
        got++;
    }
    double elapsed = got ? now_s() - t0 : 0.0;
    hv_can_stats_t s;
    hv_can_get_stats(bus, &s);
    printf("sink received=%ld expected=%ld gaps=%ld corrupt=%ld kernel_drops=%" PRIu64
           " seconds=%.3f fps=%.0f\n",
           got, n, gaps, bad, s.rx_kernel_drops, elapsed,
           elapsed > 0 ? (double)got / elapsed : 0.0);
    return (got == n && gaps == 0 && bad == 0) ? 0 : HV_EXIT_CAN_TIMEOUT;
}

int main(int argc, char **argv)
{
    opts_t o;
    if (parse_args(argc, argv, &o))
        return HV_EXIT_USAGE;
    if (!strcmp(o.command, "list"))
        return cmd_list();
    if (!strcmp(o.command, "pack"))
        return cmd_pack();
    if (!strcmp(o.command, "unpack"))
        return cmd_unpack();
    static const char *const bus_cmds[] = {"send", "send-msg", "recv", "echo",
                                           "ping", "flood",    "sink"};
    size_t c;
    for (c = 0; c < sizeof bus_cmds / sizeof *bus_cmds && strcmp(o.command, bus_cmds[c]); c++) {
    }
    if (c == sizeof bus_cmds / sizeof *bus_cmds) {
        hv_cli_usage_error(k_prog, o.command, "unknown command");
        return HV_EXIT_USAGE;
    }
    if (o.n_args > 0 && strcmp(o.command, "send")) {
        hv_cli_usage_error(k_prog, o.args[0], "unexpected argument");
        return HV_EXIT_USAGE;
    }
    hv_can_bus_t bus;
    int rc = open_bus(&o, &bus);
    if (rc != 0)
        return rc;
    switch (c) {
    case 0: rc = cmd_send(&o, &bus, 0); break;
    case 1: rc = cmd_send(&o, &bus, 1); break;
    case 2: rc = cmd_recv(&o, &bus, 0); break;
    case 3: rc = cmd_recv(&o, &bus, 1); break;
    case 4: rc = cmd_ping(&o, &bus); break;
    case 5: rc = cmd_flood(&o, &bus); break;
    default: rc = cmd_sink(&o, &bus); break;
    }
    print_stats(&bus);
    hv_can_close(&bus);
    return rc;
}
