/*
 * gaitc-run: a generated controller on a host, driven over standard input (gaitc codegen
 * --target c).  One command per line, one answer per line:
 *   s V1 .. VI   start with the first input values          -> "O1 .. OF goal"
 *   x V1 .. VI   one step: the environment chose V1 .. VI     -> "move O1 .. OF goal"
 *   a O1 .. OF   robotics semantics: may it start there      -> "1" or "0"
 *   d            the tables, as JSON (for the verifier)
 * Values are value indices, every field's (O1 .. OF) in declaration order.  With --names
 * every answer names them instead: "region=r3 gait=north L1=2 ... goal=1", a step's
 * preceded by "move=M".  A malformed line or a value out of its field's range answers
 * "error ..." and changes nothing.
 */
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include "gaitc_controller.h"

extern void gaitc_dump(FILE *out);

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
    while (fgets(line, sizeof line, stdin)) {
        if (line[0] == 'd' && (line[1] == '\n' || line[1] == 0)) {
            gaitc_dump(stdout);
        } else if ((line[0] == 's' || line[0] == 'x') && line[1] == ' ') {
            if (!read_values(line + 2, in, GAITC_INPUTS) || !gaitc_valid(in)) {
                printf("error: %d input values in range expected\n", GAITC_INPUTS);
            } else if (line[0] == 's') {
                gaitc_start(&s, in);
                started = 1;
                print_state(&s, names);
            } else if (!started) {
                printf("error: start first\n");
            } else {
                unsigned move = gaitc_step(&s, in);
                printf(names ? "move=%u " : "%u ", move);
                print_state(&s, names);
            }
        } else if (line[0] == 'a' && line[1] == ' ') {
            if (!read_values(line + 2, whole, GAITC_FIELDS) || !gaitc_valid_state(whole)) {
                printf("error: %d field values in range expected\n", GAITC_FIELDS);
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
