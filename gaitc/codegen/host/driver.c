/*
 * gaitc-run: a generated controller on a host, driven over standard input (gaitc codegen
 * --target c).  One command per line, one answer per line:
 *   s V1 .. VI   start with the first input values          -> "O1 .. OF goal"
 *   x V1 .. VI   one step: the environment chose V1 .. VI     -> "move O1 .. OF goal"
 *                inputs that break the assumptions (the monitor's verdict): with the
 *                recovery tables (codegen --recover) the step they take, "recovered move
 *                O1 .. OF goal", "degraded MASK move O1 .. OF goal" (MASK: the goals still
 *                pursued, bit j for goal j + 1) or "stopped" (no move, and none after);
 *                without them "error: the inputs break the assumptions" (nothing changes)
 *   a O1 .. OF   robotics semantics: may it start there      -> "1" or "0"
 *   d            the tables, as JSON (for the verifier)
 * Values are value indices, every field's (O1 .. OF) in declaration order.  With --names
 * every answer names them instead: "region=r3 gait=north L1=2 ... goal=1", a step's
 * preceded by "move=M", and a command's values may be names too: a value's name (its
 * label), or FIELD=NAME as the answers print it (the field must be the one at that
 * place), or still an index (a bare number is always an index, as without --names:
 * "L1=2" is level 2, a bare "2" is index 2).  Input names need the input fields' order,
 * GAITC_INPUT_FIELDS (gaitc's build passes it); compiled without it, --names answers in
 * names and reads indices only.  A malformed line, an unknown name or a value out of its
 * field's range answers "error ..." and changes nothing.
 */
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include "gaitc_controller.h"

extern void gaitc_dump(FILE *out);

#if defined(GAITC_NAMES) && defined(GAITC_INPUT_FIELDS)
#define NAMED_INPUT 1
/* per input position, its field (GAITC_INPUT_FIELDS is "{f0, f1, ...}", from the build) */
static const uint8_t input_field[GAITC_INPUTS > 0 ? GAITC_INPUTS : 1] = GAITC_INPUT_FIELDS;
static unsigned field_size[GAITC_FIELDS];

/* every field's number of values, found through gaitc_valid_state (the labels' "?" for an
 * index out of range could be a label too) */
static void find_sizes(void)
{
    uint8_t probe[GAITC_FIELDS];
    int f;
    for (f = 0; f < GAITC_FIELDS; f++) {
        unsigned v = 0;
        memset(probe, 0, sizeof probe);
        while (v < 256) {
            probe[f] = (uint8_t)v;
            if (!gaitc_valid_state(probe)) break;
            v++;
        }
        field_size[f] = v;
    }
}

/* the value of field f that the token (text, len) names: an index, NAME or FIELD=NAME;
 * -1 when it names none */
static int named_value(const char *text, size_t len, int f)
{
    const char *eq = memchr(text, '=', len);
    size_t k;
    unsigned v;
    int digits = len > 0 && len <= 3;
    for (k = 0; k < len && digits; k++)
        if (text[k] < '0' || text[k] > '9') digits = 0;
    if (digits) {
        v = (unsigned)strtoul(text, NULL, 10);
        return v < field_size[f] ? (int)v : -1;
    }
    if (eq != NULL) {
        const char *field = gaitc_field_name((uint8_t)f);
        size_t width = (size_t)(eq - text);
        if (strlen(field) != width || memcmp(field, text, width) != 0) return -1;
        len -= width + 1;
        text = eq + 1;
    }
    for (v = 0; v < field_size[f]; v++) {
        const char *label = gaitc_value_name((uint8_t)f, (uint8_t)v);
        if (strlen(label) == len && memcmp(label, text, len) == 0) return (int)v;
    }
    return -1;
}

/* read_values for --names: n tokens, the k-th a value of field fields[k] (or of field k
 * when fields is NULL) */
static int read_named(const char *text, uint8_t *values, int n, const uint8_t *fields)
{
    int k;
    for (k = 0; k < n; k++) {
        size_t len = 0;
        int v;
        while (*text == ' ') text++;
        while (text[len] != 0 && text[len] != ' ' && text[len] != '\n' && text[len] != '\r')
            len++;
        v = len ? named_value(text, len, fields ? fields[k] : k) : -1;
        if (v < 0) return 0;
        values[k] = (uint8_t)v;
        text += len;
    }
    while (*text == ' ' || *text == '\n' || *text == '\r') text++;
    return *text == 0;
}
#endif

static int read_values(const char *text, uint8_t *values, int n)
{
    int k;
    for (k = 0; k < n; k++) {
        char *end;
        long v;
        while (*text == ' ') text++;
        v = strtol(text, &end, 10);
        if (end == text || v < 0 || v > 255) return 0;
        values[k] = (uint8_t)v;
        text = end;
    }
    while (*text == ' ' || *text == '\n' || *text == '\r') text++;
    return *text == 0;
}

#ifdef NAMED_INPUT
#define ALSO (names ? " (indices, names or FIELD=NAME)" : "")
#else
#define ALSO ""
#endif

/* a command's n values: indices, or with --names (where built in) names too */
static int read_line(const char *text, uint8_t *values, int n, int names, int inputs)
{
#ifdef NAMED_INPUT
    if (names) return read_named(text, values, n, inputs ? input_field : NULL);
#else
    (void)names;
    (void)inputs;
#endif
    return read_values(text, values, n);
}

static void print_state(const gaitc_state *s, int names)
{
    int k;
    for (k = 0; k < GAITC_FIELDS; k++) {
        if (names)
            printf("%s=%s ", gaitc_field_name((uint8_t)k),
                   gaitc_value_name((uint8_t)k, s->value[k]));
        else
            printf("%d ", s->value[k]);
    }
    printf(names ? "goal=%d\n" : "%d\n", s->goal);
}

int main(int argc, char **argv)
{
    char line[4096];
    gaitc_state s;
    uint8_t in[GAITC_INPUTS + 1], whole[GAITC_FIELDS];
    int started = 0, names = argc > 1 && strcmp(argv[1], "--names") == 0;
    memset(&s, 0, sizeof s);
    if (argc > 1 && !names) {
        fprintf(stderr, "usage: gaitc-run [--names] (commands on standard input)\n");
        return 2;
    }
#ifdef NAMED_INPUT
    find_sizes();
#endif
    while (fgets(line, sizeof line, stdin)) {
        if (line[0] == 'd' && (line[1] == '\n' || line[1] == 0)) {
            gaitc_dump(stdout);
        } else if ((line[0] == 's' || line[0] == 'x') && line[1] == ' ') {
            if (!read_line(line + 2, in, GAITC_INPUTS, names, 1) || !gaitc_valid(in)) {
                printf("error: %d input values in range expected%s\n", GAITC_INPUTS, ALSO);
            } else if (line[0] == 's') {
                gaitc_start(&s, in);
                started = 1;
                print_state(&s, names);
            } else if (!started) {
                printf("error: start first\n");
            } else {
#ifdef GAITC_RECOVER
                uint16_t move = 0;
                uint8_t outcome = gaitc_step_surprise(&s, in, &move);
                if (outcome == GAITC_STOPPED) {
                    printf("stopped\n");
                } else {
                    if (outcome == GAITC_RECOVERED) printf("recovered ");
                    if (outcome == GAITC_DEGRADED) printf("degraded %u ", gaitc_kept(&s));
                    printf(names ? "move=%u " : "%u ", move);
                    print_state(&s, names);
                }
#else
                if (!gaitc_assumed(&s, in)) {
                    printf("error: the inputs break the assumptions (codegen --recover "
                           "adds what to do then)\n");
                } else {
                    unsigned move = gaitc_step(&s, in);
                    printf(names ? "move=%u " : "%u ", move);
                    print_state(&s, names);
                }
#endif
            }
        } else if (line[0] == 'a' && line[1] == ' ') {
            if (!read_line(line + 2, whole, GAITC_FIELDS, names, 0) ||
                !gaitc_valid_state(whole)) {
                printf("error: %d field values in range expected%s\n", GAITC_FIELDS, ALSO);
            } else {
                memcpy(s.value, whole, sizeof whole);
                s.goal = 0;
                started = 1;
                printf("%d\n", gaitc_accepts(&s) ? 1 : 0);
            }
        } else {
            printf("error: unknown command\n");
        }
        fflush(stdout);
    }
    return 0;
}
