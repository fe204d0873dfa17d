/*
 * gaitboard: the valve-board firmware of gaitc, line protocol v2 (docs/hardware.md).
 *
 * Target: ATmega328P at 16 MHz (TQFP-32, for ADC6/ADC7), UART at 115200 baud.
 *   valves 0..5  -> PD2..PD7, valves 6..7 -> PB0..PB1   (output high = chamber on the rail,
 *                                                        low = vented; thesis section 2.2)
 *   waveguide of leg 0..7 -> ADC0..ADC7 (phototransistor, thesis section 3.4.2)
 *   contact 0..3 -> PB2..PB5 (input, pull-up, switch to ground = touching)
 *
 * Safety rules enforced here, on the board, whatever the host does:
 *   - every valve is vented at power-on and after any reset (first code to run, .init3);
 *   - a malformed command, a byte that is not printable ASCII, a line longer than LINE_MAX
 *     or a receive-buffer overrun vents at once (the answer is ERR once the line ends);
 *   - no valid command or heartbeat for the watchdog period (W, default 500 ms) vents;
 *   - the hardware watchdog timer (250 ms) resets a hung firmware, which then vents.
 */
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <avr/wdt.h>
#include <stdint.h>

#define FIRMWARE "gaitboard/2.0"
#define VALVES 8
#define LEGS 8
#define CONTACTS 4
#define LINE_MAX 48          /* characters of one command, its '\n' not counted */
#define RX_SIZE 64           /* receive ring buffer, a power of two */
#define WD_DEFAULT 500       /* ms without a valid command before the board vents */
#define WD_MIN 50
#define WD_MAX 10000

uint8_t reset_cause __attribute__((section(".noinit")));

/* Runs before main and before .data is copied: vent, then stop a watchdog left running. */
void early_vent(void) __attribute__((naked, used, section(".init3")));
void early_vent(void)
{
    PORTD &= 0x03;
    DDRD |= 0xFC;
    PORTB &= (uint8_t)~0x03;
    DDRB |= 0x03;
    reset_cause = MCUSR;
    MCUSR = 0;
    wdt_disable();
}

static volatile uint32_t now_ms;
static volatile uint8_t rx_buf[RX_SIZE];
static volatile uint8_t rx_head, rx_tail, rx_overrun;

static char line[LINE_MAX + 1];
static uint8_t line_len;
static uint8_t discarding;   /* why the rest of the line is thrown away: 0 it is not,
                              * 1 too long, 2 a malformed byte, 3 a receive overrun */
static uint16_t wd_period = WD_DEFAULT;
static uint32_t last_valid;
static uint8_t valves;       /* bit i = valve i */

static uint16_t adc_filtered[LEGS]; /* x16: exponential average, a new sample weighs 1/8 */
static uint8_t adc_channel, adc_primed;

ISR(TIMER0_COMPA_vect) { now_ms++; }

ISR(USART_RX_vect)
{
    uint8_t c = UDR0;
    uint8_t next = (uint8_t)((rx_head + 1) & (RX_SIZE - 1));
    if (next == rx_tail) {
        rx_overrun = 1;
        return;
    }
    rx_buf[rx_head] = c;
    rx_head = next;
}

static uint32_t millis(void)
{
    uint32_t t;
    cli();
    t = now_ms;
    sei();
    return t;
}

static volatile uint16_t adc_now[LEGS], adc_low[LEGS];

/* Valve i actuates leg i: when it opens, a new actuation cycle of that leg's waveguide
 * starts and its lowest value is measured afresh. */
static void set_valves(uint8_t bits)
{
    uint8_t opened = (uint8_t)(bits & (uint8_t)~valves), i;
    uint8_t d = (uint8_t)((PORTD & 0x03) | (uint8_t)((bits & 0x3F) << 2));
    uint8_t b = (uint8_t)((PORTB & (uint8_t)~0x03) | ((bits >> 6) & 0x03));
    cli();
    PORTD = d;
    PORTB = b;
    for (i = 0; i < LEGS; i++)
        if (opened & (1 << i)) adc_low[i] = adc_now[i];
    sei();
    valves = bits;
}

static void vent(void) { set_valves(0); }

static void put(char c)
{
    while (!(UCSR0A & (1 << UDRE0))) {
    }
    UDR0 = (uint8_t)c;
}

static void puts_(const char *s)
{
    while (*s) put(*s++);
}

static void put_uint(uint16_t v)
{
    char digits[6];
    uint8_t n = 0;
    do {
        digits[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (n) put(digits[--n]);
}

static void end_line(void) { puts_("\r\n"); }

#ifdef GAITC_BOARD
static uint8_t autonomous;   /* 1 while the board runs the task on its own */
#endif

static void refuse(const char *why)
{
#ifdef GAITC_BOARD
    autonomous = 0;
#endif
    vent();
    puts_("ERR ");
    puts_(why);
    puts_("; vented");
    end_line();
}

static void adc_start(uint8_t channel)
{
    ADMUX = (uint8_t)((1 << REFS0) | channel);   /* AVcc reference */
    ADCSRA |= (1 << ADSC);
}

/* A conversion finished: one waveguide sample, round robin over the legs (about 0.8 ms per
 * leg).  The samples are filtered (time constant about 7 ms) and the lowest filtered value
 * since the leg's valve last opened is kept: the dip of its last actuation cycle. */
ISR(ADC_vect)
{
    uint16_t sample = ADC;
    uint16_t *f = &adc_filtered[adc_channel];
    if (adc_primed < LEGS) {
        *f = (uint16_t)(sample << 4);
        adc_primed++;
    } else {
        *f = (uint16_t)(*f - (*f >> 3) + (sample << 1));
    }
    uint16_t v = (uint16_t)((*f + 8) >> 4);
    adc_now[adc_channel] = v;
    if (v < adc_low[adc_channel]) adc_low[adc_channel] = v;
    adc_channel = (uint8_t)((adc_channel + 1) % LEGS);
    adc_start(adc_channel);
}

static uint16_t read_adc(volatile uint16_t *value)
{
    uint16_t v;
    cli();
    v = *value;
    sei();
    return v;
}

static void reply_sensors(void)
{
    uint8_t i;
    puts_("S a=");
    for (i = 0; i < LEGS; i++) {
        if (i) put(',');
        put_uint(read_adc(&adc_now[i]));
    }
    puts_(" lo=");
    for (i = 0; i < LEGS; i++) {
        if (i) put(',');
        put_uint(read_adc(&adc_low[i]));
    }
    puts_(" c=");
    for (i = 0; i < CONTACTS; i++) put((PINB & (1 << (PB2 + i))) ? '0' : '1');
    end_line();
}

static const char *reset_name(void)
{
    if (reset_cause & (1 << WDRF)) return "watchdog";
    if (reset_cause & (1 << BORF)) return "brownout";
    if (reset_cause & (1 << EXTRF)) return "external";
    return "power";
}

#ifdef GAITC_CONTROLLER
#include "gaitc_controller.h" /* GAITC_MONITOR, for the PING answer */
#endif

static void reply_pong(void)
{
    puts_("PONG " FIRMWARE " proto=2 valves=");
    put_uint(VALVES);
    puts_(" legs=");
    put_uint(LEGS);
    puts_(" contacts=");
    put_uint(CONTACTS);
    puts_(" wd=");
    put_uint(wd_period);
    puts_(" reset=");
    puts_(reset_name());
#ifdef GAITC_CONTROLLER
    /* whether the linked controller checks the spec's assumptions (codegen --no-monitor) */
    puts_(GAITC_MONITOR ? " monitor=1" : " monitor=0");
#endif
    end_line();
}

/* "W 500": digits only, WD_MIN..WD_MAX; returns 0 when malformed. */
static uint16_t parse_period(const char *s)
{
    uint32_t v = 0;
    uint8_t n = 0;
    for (; *s; s++, n++) {
        if (*s < '0' || *s > '9' || n >= 5) return 0;
        v = v * 10 + (uint32_t)(*s - '0');
    }
    return (n && v >= WD_MIN && v <= WD_MAX) ? (uint16_t)v : 0;
}

static uint8_t same(const char *a, const char *b)
{
    while (*a && *a == *b) a++, b++;
    return *a == *b;
}

#ifdef GAITC_CONTROLLER
/* A generated controller linked in (gaitc codegen --target avr): "C s VVV" starts it from
 * the first input values, "C x VVV" makes one step; VVV holds one base-36 digit per input
 * field (0-9, a-z).  The answer: "M <move> g=<goal> o=<output values, base 36>".  With
 * recovery tables (GAITC_RECOVER), "C r VVV" makes a step whatever the inputs and answers
 * "R <allowed|recovered|degraded|stopped> k=<goals kept, a bit mask> m=<move> g= o=". */
#include "gaitc_controller.h"

static gaitc_state controller;
static uint8_t controller_started;

static char digit36(uint8_t v) { return (char)(v < 10 ? '0' + v : 'a' + v - 10); }

/* n base-36 digits (0-9, a-z) from s into values; 0 when one is not such a digit */
static uint8_t read_digits36(const char *s, uint8_t *values, uint8_t n)
{
    uint8_t k;
    for (k = 0; k < n; k++) {
        char c = s[k];
        if (c >= '0' && c <= '9') values[k] = (uint8_t)(c - '0');
        else if (c >= 'a' && c <= 'z') values[k] = (uint8_t)(c - 'a' + 10);
        else return 0;
    }
    return 1;
}

/* " g=<goal> o=<every field's value, base 36>" and the end of the line */
static void put_state(void)
{
    uint8_t k;
    puts_(" g=");
    put_uint(controller.goal);
    puts_(" o=");
    for (k = 0; k < GAITC_FIELDS; k++) put(digit36(controller.value[k]));
    end_line();
}

#ifdef GAITC_RECOVER
static const char *outcome_word(uint8_t outcome)
{
    if (outcome == GAITC_RECOVERED) return "recovered";
    if (outcome == GAITC_DEGRADED) return "degraded";
    if (outcome == GAITC_STOPPED) return "stopped";
    return "allowed";
}

/* "R <outcome> k=<goal mask>": what a step whatever the inputs did (gaitc codegen
 * --recover); the rest of the line is the caller's */
static void put_outcome(uint8_t outcome)
{
    puts_("R ");
    puts_(outcome_word(outcome));
    puts_(" k=");
    put_uint(gaitc_kept(&controller));
}
#define C_KINDS(c) ((c) == 's' || (c) == 'x' || (c) == 'r')
#else
#define C_KINDS(c) ((c) == 's' || (c) == 'x')
#endif

static uint8_t controller_command(void)
{
    uint8_t in[GAITC_INPUTS + 1];
    uint16_t move = 0;
    if (line_len != 4 + GAITC_INPUTS || line[1] != ' ' || line[3] != ' '
        || !C_KINDS(line[2])) {
        refuse("C needs s or x and one digit per input");
        return 0;
    }
    if (!read_digits36(line + 4, in, GAITC_INPUTS)) {
        refuse("C needs base-36 digits");
        return 0;
    }
    if (!gaitc_valid(in)) {
        refuse("C input out of range");
        return 0;
    }
    if (line[2] == 's') {
        gaitc_start(&controller, in);
        controller_started = 1;
    } else if (!controller_started) {
        refuse("C x before C s");
        return 0;
#ifdef GAITC_RECOVER
    } else if (line[2] == 'r') {
        /* a step whatever the inputs: "R <outcome> k=<mask> m=<move> g= o=" (stopped:
         * no move, every valve vented) */
        uint8_t outcome = gaitc_step_surprise(&controller, in, &move);
        if (outcome == GAITC_STOPPED) {
            vent();
            move = 0;
        }
        put_outcome(outcome);
        puts_(" m=");
        put_uint(move);
        put_state();
        return 1;
#endif
    } else {
        move = gaitc_step(&controller, in);
    }
    puts_("M ");
    put_uint(move);
    put_state();
    return 1;
}

#ifdef GAITC_BOARD
/* The task run by the board alone (gaitc codegen --target avr with valve primitives):
 * "A MS VVV" starts the controller from the first inputs VVV and then, step after step, puts
 * the chosen gait's valve sequence on the pins (MS ms per valve state), vents, grades the
 * legs the gait used from their waveguide dips and asks the controller for the next gait.
 * Each step is reported as "A <step> m=<move> g=<goal> o=<field values>"; the host only
 * watches, and its silence no longer vents.  The board vents and stops on its own checks:
 * a grading out of range, or inputs the spec's assumptions do not allow (the controller's
 * guarantee would no longer hold).  "H K" sets the active hazard (K a base-36 digit),
 * "AX" stops. */
#include "gaitc_board.h"

#define SETTLE_MS 40        /* after venting, before the waveguides are read at rest */

static uint8_t auto_phase, auto_index, auto_hazard;
static uint16_t auto_dwell, auto_steps, auto_first, auto_last;
static uint32_t auto_since;

static uint8_t input_of(uint8_t field) { return pgm_read_byte(&board_input_pos[field]); }

static void auto_begin_gait(void)
{
    uint8_t gait = controller.value[GAITC_BOARD_GAIT_FIELD];
    auto_first = pgm_read_word(&board_sequence_first[gait]);
    auto_last = pgm_read_word(&board_sequence_first[gait + 1]);
    auto_index = 0;
    auto_phase = 0;
    auto_since = millis();
    if (auto_first < auto_last) set_valves(pgm_read_byte(&board_sequence[auto_first]));
}

static uint8_t grade(uint8_t channel)
{
    uint16_t rest = read_adc(&adc_now[channel]), low = read_adc(&adc_low[channel]);
    uint16_t feature = rest > low ? (uint16_t)(1000UL * (rest - low) / rest) : 0;
    uint8_t level = pgm_read_byte(&board_top_level[channel]), k;
    uint8_t count = pgm_read_byte(&board_threshold_count[channel]);
    for (k = 0; k < count; k++)
        if (feature < pgm_read_word(&board_threshold[channel][k]) && level) level--;
    return level;
}

static void auto_report(uint16_t move)
{
    puts_("A ");
    put_uint(auto_steps);
    puts_(" m=");
    put_uint(move);
    put_state();
}

static void auto_step(void)
{
    uint8_t in[GAITC_INPUTS + 1], f, ch, used = 0, i;
    uint16_t move;
    for (i = auto_first; i < auto_last; i++) used |= pgm_read_byte(&board_sequence[i]);
    for (f = 0; f < GAITC_FIELDS; f++)
        if (input_of(f) != 255) in[input_of(f)] = controller.value[f];
    for (ch = 0; ch < 8; ch++) {
        f = pgm_read_byte(&board_leg_field[ch]);
        if (f != 255 && (used & (1 << ch))) in[input_of(f)] = grade(ch);
    }
    if (GAITC_BOARD_HAZARD_FIELD != 255) in[input_of(GAITC_BOARD_HAZARD_FIELD)] = auto_hazard;
#ifdef GAITC_RECOVER
    /* a surprise recovers or degrades (reported as "R <outcome> k=<mask> s=<step>" before
     * the step's A line) or stops: then the board vents, as without recovery */
    if (!gaitc_valid(in)) {
        refuse("sensed inputs break the assumptions");
        return;
    }
    {
        uint8_t outcome = gaitc_step_surprise(&controller, in, &move);
        if (outcome != GAITC_ALLOWED) {
            put_outcome(outcome);
            puts_(" s=");
            put_uint((uint16_t)(auto_steps + 1));
            end_line();
        }
        if (outcome == GAITC_STOPPED) {
            refuse("sensed inputs break the assumptions");
            return;
        }
    }
#else
    if (!gaitc_valid(in) || !gaitc_assumed(&controller, in)) {
        refuse("sensed inputs break the assumptions");
        return;
    }
    move = gaitc_step(&controller, in);
#endif
    auto_steps++;
    auto_report(move);
    auto_begin_gait();
}

static void auto_tick(void)
{
    uint32_t now = millis();
    if (auto_phase == 0) {
        if (now - auto_since < auto_dwell) return;
        auto_index++;
        auto_since = now;
        if (auto_first + auto_index < auto_last) {
            set_valves(pgm_read_byte(&board_sequence[auto_first + auto_index]));
        } else {
            vent();
            auto_phase = 1;
        }
    } else if (now - auto_since >= SETTLE_MS) {
        auto_step();
    }
}

static uint8_t auto_command(void)
{
    uint8_t in[GAITC_INPUTS + 1], n = 0;
    uint16_t dwell = 0;
    const char *p = line + 2;
    if (same(line, "AX")) {
        autonomous = 0;
        vent();
        puts_("OK stopped");
        end_line();
        return 1;
    }
    if (line[0] == 'H' && line[1] == ' ' && line_len == 3) {
        if (!read_digits36(line + 2, &auto_hazard, 1)) {
            refuse("H needs a base-36 digit");
            return 0;
        }
        puts_("OK");
        end_line();
        return 1;
    }
    while (*p >= '0' && *p <= '9' && n < 5) dwell = (uint16_t)(dwell * 10 + (*p++ - '0')), n++;
    if (line[1] != ' ' || !n || dwell < 20 || dwell > 5000 || *p != ' '
        || (uint8_t)(line + line_len - (p + 1)) != GAITC_INPUTS) {
        refuse("A needs a dwell of 20..5000 ms and one digit per input");
        return 0;
    }
    if (!read_digits36(p + 1, in, GAITC_INPUTS) || !gaitc_valid(in)) {
        refuse("A input out of range");
        return 0;
    }
    gaitc_start(&controller, in);
    controller_started = 1;
    auto_hazard = GAITC_BOARD_HAZARD_FIELD != 255 ? controller.value[GAITC_BOARD_HAZARD_FIELD] : 0;
    auto_dwell = dwell;
    auto_steps = 0;
    autonomous = 1;
    auto_report(0);
    auto_begin_gait();
    return 1;
}
#endif
#endif

static void execute(void)
{
    if (same(line, "PING")) {
        reply_pong();
    } else if (same(line, "HB")) {
        puts_("OK");
        end_line();
    } else if (same(line, "S")) {
        reply_sensors();
    } else if (line[0] == 'V' && line[1] == ' ') {
        uint8_t bits = 0, i;
        if (line_len != 2 + VALVES) {
            refuse("V needs 8 valve bits");
            return;
        }
        for (i = 0; i < VALVES; i++) {
            char c = line[2 + i];
            if (c != '0' && c != '1') {
                refuse("V needs 8 valve bits");
                return;
            }
            if (c == '1') bits |= (uint8_t)(1 << i);
        }
#ifdef GAITC_BOARD
        autonomous = 0;
#endif
        set_valves(bits);
        puts_("OK");
        end_line();
    } else if (line[0] == 'W' && line[1] == ' ') {
        uint16_t period = parse_period(line + 2);
        if (!period) {
            refuse("W needs a period of 50..10000 ms");
            return;
        }
        wd_period = period;
        puts_("OK wd=");
        put_uint(wd_period);
        end_line();
#ifdef GAITC_CONTROLLER
    } else if (line[0] == 'C') {
        if (!controller_command()) return;
#ifdef GAITC_BOARD
    } else if (line[0] == 'A' || (line[0] == 'H' && line[1] == ' ')) {
        if (!auto_command()) return;
#endif
#endif
    } else if (same(line, "HANG")) {
        /* self-test of the hardware watchdog: stop serving; the reset vents */
        cli();
        for (;;) {
        }
    } else {
        refuse("unknown command");
        return;
    }
    last_valid = millis();
}

static void receive(uint8_t c)
{
    if (c == '\n') {
        if (discarding == 1) refuse("line too long");
        else if (discarding == 2) refuse("malformed byte");
        else if (discarding == 3) refuse("receive overrun");
        else if (line_len) {
            line[line_len] = 0;
            execute();
        }
        line_len = 0;
        discarding = 0;
        return;
    }
    if (c == '\r' || discarding) return;
    if (c < 0x20 || c > 0x7E) {
        vent();
        discarding = 2;
    } else if (line_len >= LINE_MAX) {
        vent();
        discarding = 1;
    } else {
        line[line_len++] = (char)c;
    }
}

int main(void)
{
    uint8_t i;
    vent();
    DDRB &= (uint8_t)~0x3C;                  /* contacts: inputs with pull-ups */
    PORTB |= 0x3C;
    TCCR0A = (1 << WGM01);                   /* timer 0: CTC, 16 MHz / 64 / 250 = 1 kHz */
    OCR0A = 249;
    TCCR0B = (1 << CS01) | (1 << CS00);
    TIMSK0 = (1 << OCIE0A);
    UCSR0A = (1 << U2X0);                    /* 115200 baud: UBRR 16 with U2X */
    UBRR0 = 16;
    UCSR0B = (1 << RXEN0) | (1 << TXEN0) | (1 << RXCIE0);
    UCSR0C = (1 << UCSZ01) | (1 << UCSZ00);
    ADCSRA = (1 << ADEN) | (1 << ADIE) | (1 << ADPS2) | (1 << ADPS1) | (1 << ADPS0);
    for (i = 0; i < LEGS; i++) adc_low[i] = 0x3FF;
    adc_start(0);
    wdt_enable(WDTO_250MS);
    sei();
    set_sleep_mode(SLEEP_MODE_IDLE);
    for (;;) {
        wdt_reset();
        while (rx_tail != rx_head) {
            uint8_t c = rx_buf[rx_tail];
            rx_tail = (uint8_t)((rx_tail + 1) & (RX_SIZE - 1));
            receive(c);
        }
        if (rx_overrun) {
            rx_overrun = 0;
            vent();
            discarding = 3;
        }
#ifdef GAITC_BOARD
        if (autonomous) auto_tick();
        else
#endif
        if (valves && millis() - last_valid >= wd_period) vent();
        /* idle until the next interrupt (the 1 ms tick at the latest); no byte is missed:
         * interrupts are enabled only by the instruction before sleep */
        cli();
        if (rx_tail == rx_head && !rx_overrun) {
            sleep_enable();
            sei();
            sleep_cpu();
            sleep_disable();
        }
        sei();
    }
}
