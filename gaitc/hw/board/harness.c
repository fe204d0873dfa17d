/*
 * gaitboard-sim: runs the real gaitboard firmware image (an ELF file) in simavr, in real
 * time, as the valve board of `gaitc drive --backend serial`.
 *
 *   gaitboard-sim FIRMWARE.elf [--record FILE] [--watchdog-ms N] [--adc MV] [--depth D]
 *                 [--noise MV]
 *
 * The board's UART is a pseudo-terminal whose path is the first line printed.  Every
 * change of the valve pins (PD2..PD7, PB0..PB1) is written to FILE as a JSON line
 * {"t_ms": simulated milliseconds, "valves": "0101..."} (valve 0 first; changes less than
 * COALESCE_US apart, such as the two port writes of one valve command, are one line).
 * Each waveguide input follows its leg's valve (valve i bends leg i), as an actuator would:
 *   mV = rest * (1 - depth * bend) + noise,  bend -> valve state with a 10 ms time constant,
 * so a pressurised healthy leg (depth 0.6) dims its waveguide by 60 % and a damaged one less
 * (thesis section 3.4.2, Figure 3.5).
 * Standard input is a control channel, one command a line:
 *   adc CH MV        waveguide CH (0..7) reads MV millivolts at rest (0..5000)
 *   depth CH D       leg CH dims its waveguide by the fraction D (0..1) when fully bent
 *   wear CH D1 D2 .. the depth of leg CH's next actuation cycles, one per cycle (up to 16;
 *                    the last one stays): a progressively damaged actuator (Figure 3.5)
 *   contact I 0|1    contact input I (0..3) touching (1) or not (0)
 *   time             prints "t_ms=<simulated ms>"
 * It runs until killed (SIGTERM and SIGINT end it cleanly).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <simavr/avr_adc.h>
#include <simavr/avr_extint.h>
#include <simavr/avr_ioport.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>

#define VALVES 8
#define LEGS 8
#define CONTACTS 4
#define FREQUENCY 16000000UL
#define COALESCE_US 50
#define BATCH 2000 /* instructions between looks at the pty, stdin and the clock */
#define SLICE_US 200

#define BEND_TAU_MS 10.0
#define INPUT_EVERY_MS 0.25

static const char valve_port[VALVES] = {'D', 'D', 'D', 'D', 'D', 'D', 'B', 'B'};
static const int valve_bit[VALVES] = {2, 3, 4, 5, 6, 7, 0, 1};

static avr_t *avr;
static avr_irq_t *uart_in;
static avr_irq_t *adc_in[LEGS];
static avr_irq_t *contact_in[CONTACTS];
static int master = -1;
static int xon = 1;
static FILE *record;
static char pins[VALVES + 1], written[VALVES + 1];
static avr_cycle_count_t pending_since, pending_at;
static int pending;
static volatile sig_atomic_t stopping;
static avr_cycle_count_t cycle_base, last_cycle; /* simavr may restart its count on reset */
static char boot_reply[128];
static size_t boot_len;
static int booting = 1;
static double rest_mv[LEGS], depth[LEGS], bend[LEGS], noise_mv;
static uint32_t shown_mv[LEGS], noise_state = 12345;
static avr_cycle_count_t inputs_at;
#define WEAR_MAX 16
static double wear[LEGS][WEAR_MAX];
static int wear_len[LEGS], wear_next[LEGS];

static avr_cycle_count_t now_cycles(void)
{
    if (avr->cycle < last_cycle) cycle_base += last_cycle;
    last_cycle = avr->cycle;
    return cycle_base + avr->cycle;
}

static double to_ms(avr_cycle_count_t cycles) { return (double)cycles * 1000.0 / FREQUENCY; }

static void on_pin(struct avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq;
    int valve = (int)(intptr_t)param;
    char bit = value ? '1' : '0';
    if (pins[valve] == bit) return;
    pins[valve] = bit;
    if (bit == '1' && valve < LEGS && wear_next[valve] < wear_len[valve])
        depth[valve] = wear[valve][wear_next[valve]++]; /* a new actuation cycle begins */
    if (!pending) pending_at = now_cycles();
    pending = 1;
    pending_since = now_cycles();
}

static void flush_pins(int force)
{
    if (!pending) return;
    if (!force && now_cycles() - pending_since < FREQUENCY / 1000000 * COALESCE_US) return;
    pending = 0;
    if (strcmp(pins, written) == 0) return;
    memcpy(written, pins, sizeof pins);
    if (record) {
        fprintf(record, "{\"t_ms\": %.3f, \"valves\": \"%s\"}\n", to_ms(pending_at), pins);
        fflush(record);
    }
}

static void on_uart_out(struct avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq, (void)param;
    unsigned char c = (unsigned char)value;
    if (booting) {
        if (boot_len < sizeof boot_reply - 1) boot_reply[boot_len++] = (char)c;
        return;
    }
    if (write(master, &c, 1) < 0) {
        /* nobody reads the pty and its buffer is full: the byte is lost, as on a wire */
    }
}

/* the UART's receive FIFO has room (param 1) or is full (param 0) */
static void on_flow(struct avr_irq_t *irq, uint32_t value, void *param)
{
    (void)irq, (void)value;
    xon = (int)(intptr_t)param;
}

static double wall_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1000.0 + ts.tv_nsec / 1e6;
}

static void update_inputs(int force);

/* simavr's own sleep callback would sleep in real time too; the main loop paces instead */
static void no_sleep(avr_t *core, avr_cycle_count_t how_long)
{
    (void)core, (void)how_long;
}

/* Up to BATCH instructions, and no more than SLICE_US of simulated time (a sleeping
 * firmware skips ahead from one interrupt to the next in one step). */
static void run_batch(void)
{
    avr_cycle_count_t end = now_cycles() + FREQUENCY / 1000000 * SLICE_US;
    for (int i = 0; i < BATCH && now_cycles() < end; i++) {
        int state = avr_run(avr);
        if (state == cpu_Done || state == cpu_Crashed) {
            fprintf(stderr, "gaitboard-sim: the firmware stopped (state %d)\n", state);
            flush_pins(1);
            exit(1);
        }
    }
    flush_pins(0);
    update_inputs(0);
}

static double noise(void)
{
    noise_state = noise_state * 1103515245u + 12345u; /* deterministic */
    return ((double)((noise_state >> 8) & 0xFFFF) / 32767.5 - 1.0) * noise_mv;
}

/* The waveguides: each leg bends toward its valve's state and dims its light. */
static void update_inputs(int force)
{
    avr_cycle_count_t now = now_cycles();
    double dt = to_ms(now - inputs_at);
    if (!force && dt < INPUT_EVERY_MS) return;
    inputs_at = now;
    double keep = exp(-dt / BEND_TAU_MS);
    for (int l = 0; l < LEGS; l++) {
        double target = pins[l] == '1' ? 1.0 : 0.0;
        bend[l] = target + (bend[l] - target) * keep;
        double mv = rest_mv[l] * (1.0 - depth[l] * bend[l]) + noise();
        uint32_t out = mv < 0 ? 0 : mv > 5000 ? 5000 : (uint32_t)(mv + 0.5);
        if (force || out != shown_mv[l]) {
            shown_mv[l] = out;
            avr_raise_irq(adc_in[l], out);
        }
    }
}

static void feed_uart(void)
{
    unsigned char buf[1];
    while (xon) {
        ssize_t n = read(master, buf, 1);
        if (n <= 0) return; /* EAGAIN, or EIO while no program has the pty open */
        avr_raise_irq(uart_in, buf[0]);
    }
}

static void control(char *cmd)
{
    int a, b;
    double d;
    if (sscanf(cmd, "adc %d %d", &a, &b) == 2 && a >= 0 && a < LEGS && b >= 0 && b <= 5000) {
        rest_mv[a] = b;
        update_inputs(1);
    } else if (sscanf(cmd, "depth %d %lf", &a, &d) == 2 && a >= 0 && a < LEGS && d >= 0 &&
               d <= 1) {
        depth[a] = d;
    } else if (sscanf(cmd, "wear %d %n", &a, &b) == 1 && a >= 0 && a < LEGS) {
        char *p = cmd + b, *end;
        wear_len[a] = wear_next[a] = 0;
        for (double w = strtod(p, &end); end != p && wear_len[a] < WEAR_MAX;
             p = end, w = strtod(p, &end))
            if (w >= 0 && w <= 1) wear[a][wear_len[a]++] = w;
    } else if (sscanf(cmd, "contact %d %d", &a, &b) == 2 && a >= 0 && a < CONTACTS &&
               (b == 0 || b == 1)) {
        avr_raise_irq(contact_in[a], b ? 0 : 1); /* touching pulls the input low */
    } else if (strncmp(cmd, "time", 4) == 0) {
        printf("t_ms=%.3f\n", to_ms(now_cycles()));
        fflush(stdout);
    } else if (cmd[0]) {
        fprintf(stderr, "gaitboard-sim: unknown control command '%s'\n", cmd);
    }
}

static void read_control(void)
{
    static char buf[256];
    static size_t len;
    static int closed;
    char c;
    struct pollfd ready = {STDIN_FILENO, POLLIN, 0};
    while (!closed && poll(&ready, 1, 0) > 0) {
        ssize_t n = read(STDIN_FILENO, &c, 1);
        if (n == 0) closed = 1;
        if (n <= 0) return;
        if (c == '\n' || len == sizeof buf - 1) {
            buf[len] = 0;
            control(buf);
            len = 0;
        } else {
            buf[len++] = c;
        }
    }
}

static void stop(int sig)
{
    (void)sig;
    stopping = 1;
}

static int open_pty(void)
{
    int fd = posix_openpt(O_RDWR | O_NOCTTY);
    if (fd < 0 || grantpt(fd) || unlockpt(fd)) return -1;
    /* hold the terminal side open (raw) so that a host closing it never loses our settings */
    int slave = open(ptsname(fd), O_RDWR | O_NOCTTY);
    struct termios raw;
    if (slave < 0 || tcgetattr(slave, &raw)) return -1;
    cfmakeraw(&raw);
    tcsetattr(slave, TCSANOW, &raw);
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    return fd;
}

static void boot(int watchdog_ms)
{
    double until = to_ms(now_cycles()) + 20; /* let the firmware start */
    while (to_ms(now_cycles()) < until) run_batch();
    if (watchdog_ms) {
        char cmd[32];
        snprintf(cmd, sizeof cmd, "W %d\n", watchdog_ms);
        for (char *p = cmd; *p; p++) {
            avr_raise_irq(uart_in, (uint8_t)*p);
            run_batch();
        }
        until = to_ms(now_cycles()) + 20;
        while (to_ms(now_cycles()) < until) run_batch();
        if (!strstr(boot_reply, "OK wd=")) {
            fprintf(stderr, "gaitboard-sim: the firmware refused --watchdog-ms %d: %s\n",
                    watchdog_ms, boot_reply);
            exit(2);
        }
    }
    booting = 0;
}

int main(int argc, char **argv)
{
    const char *image = NULL, *record_path = NULL;
    int watchdog_ms = 0, adc_mv = 4000;
    double start_depth = 0.6;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--record") && i + 1 < argc) record_path = argv[++i];
        else if (!strcmp(argv[i], "--watchdog-ms") && i + 1 < argc) watchdog_ms = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--adc") && i + 1 < argc) adc_mv = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--depth") && i + 1 < argc) start_depth = atof(argv[++i]);
        else if (!strcmp(argv[i], "--noise") && i + 1 < argc) noise_mv = atof(argv[++i]);
        else if (!image && argv[i][0] != '-') image = argv[i];
        else image = NULL, i = argc;
    }
    if (!image) {
        fprintf(stderr, "usage: gaitboard-sim FIRMWARE.elf [--record FILE] "
                        "[--watchdog-ms N] [--adc MV] [--depth D] [--noise MV]\n");
        return 2;
    }
    elf_firmware_t fw;
    memset(&fw, 0, sizeof fw);
    fflush(stdout);
    int out = dup(STDOUT_FILENO), null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO); /* simavr's loader chats on stdout; the pty path is line 1 */
    int unreadable = elf_read_firmware(image, &fw);
    if (!unreadable && (avr = avr_make_mcu_by_name("atmega328p")) && !avr_init(avr)) {
        avr->log = 0;
        avr_load_firmware(avr, &fw);
    }
    fflush(stdout);
    dup2(out, STDOUT_FILENO);
    close(out);
    close(null);
    if (unreadable) {
        fprintf(stderr, "gaitboard-sim: cannot read the firmware image %s\n", image);
        return 1;
    }
    if (!avr) {
        fprintf(stderr, "gaitboard-sim: simavr has no atmega328p\n");
        return 1;
    }
    avr->frequency = FREQUENCY;
    avr->avcc = avr->vcc = 5000;
    avr->log = 0;
    avr->sleep = no_sleep;
    /* INT0/INT1 are valve pins here and never enabled as interrupts; simavr would otherwise
     * poll their low level on every cycle */
    avr_extint_set_strict_lvl_trig(avr, 0, 0);
    avr_extint_set_strict_lvl_trig(avr, 1, 0);
    if (record_path && !(record = fopen(record_path, "w"))) {
        fprintf(stderr, "gaitboard-sim: cannot write %s: %s\n", record_path, strerror(errno));
        return 1;
    }
    memset(pins, '0', VALVES);
    memcpy(written, pins, sizeof pins);
    if (record) fprintf(record, "{\"t_ms\": 0.000, \"valves\": \"%s\"}\n", pins), fflush(record);
    for (int v = 0; v < VALVES; v++)
        avr_irq_register_notify(
            avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ(valve_port[v]), valve_bit[v]), on_pin,
            (void *)(intptr_t)v);
    for (int c = 0; c < CONTACTS; c++) {
        contact_in[c] = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 2 + c);
        avr_raise_irq(contact_in[c], 1);
    }
    for (int l = 0; l < LEGS; l++) {
        adc_in[l] = avr_io_getirq(avr, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + l);
        rest_mv[l] = adc_mv;
        depth[l] = start_depth;
    }
    update_inputs(1);
    uint32_t flags = 0; /* no stdio echo, no host sleep while the firmware polls */
    avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
    uart_in = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                            on_uart_out, NULL);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON),
                            on_flow, (void *)1);
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                            on_flow, (void *)0);
    if ((master = open_pty()) < 0) {
        fprintf(stderr, "gaitboard-sim: cannot create a pseudo-terminal: %s\n", strerror(errno));
        return 1;
    }
    signal(SIGTERM, stop);
    signal(SIGINT, stop);
    signal(SIGPIPE, SIG_IGN);
    boot(watchdog_ms);
    printf("%s\n", ptsname(master));
    fflush(stdout);
    double start_wall = wall_ms(), start_sim = to_ms(now_cycles());
    while (!stopping) {
        run_batch();
        feed_uart();
        read_control();
        double ahead = (to_ms(now_cycles()) - start_sim) - (wall_ms() - start_wall);
        if (ahead > 1.0) {
            struct timespec ts = {0, (long)(ahead * 1e6)};
            nanosleep(&ts, NULL);
        }
    }
    flush_pins(1);
    if (record) fclose(record);
    return 0;
}
