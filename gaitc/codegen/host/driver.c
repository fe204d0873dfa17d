/*
 * gaitc-run: a generated controller on a host, driven over standard input (gaitc codegen
 * --target c --run).  One command per line, one answer per line:
 *   s V1 .. VI   start with the first input values          -> "O1 .. OO goal"
 *   x V1 .. VI   one step: the environment chose V1 .. VI     -> "move O1 .. OO goal"
 *   a O1..       robotics semantics: may it start there      -> "1" or "0"
 *   d            the tables, as JSON (for the verifier)
 * A malformed line or an input out of range answers "error ..." and changes nothing.
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

int main(void)
{
    char line[4096];
    gaitc_state s;
    uint8_t in[GAITC_INPUTS + 1];
    int started = 0, k;
    memset(&s, 0, sizeof s);
    while (fgets(line, sizeof line, stdin)) {
        if (line[0] == 'd') {
            gaitc_dump(stdout);
        } else if ((line[0] == 's' || line[0] == 'x') && line[1] == ' ') {
            if (!read_values(line + 2, in, GAITC_INPUTS) || !gaitc_valid(in)) {
                printf("error: %d input values in range expected\n", GAITC_INPUTS);
            } else if (line[0] == 's') {
                gaitc_start(&s, in);
                started = 1;
                for (k = 0; k < GAITC_FIELDS; k++) printf("%d ", s.value[k]);
                printf("%d\n", s.goal);
            } else if (!started) {
                printf("error: start first\n");
            } else {
                unsigned move = gaitc_step(&s, in);
                printf("%u", move);
                for (k = 0; k < GAITC_FIELDS; k++) printf(" %d", s.value[k]);
                printf(" %d\n", s.goal);
            }
        } else if (line[0] == 'a' && line[1] == ' ') {
            if (!read_values(line + 2, s.value, GAITC_FIELDS)) printf("error: field values\n");
            else {
                s.goal = 0;
                started = 1;
                printf("%d\n", gaitc_accepts(&s));
            }
        } else {
            printf("error: unknown command\n");
        }
        fflush(stdout);
    }
    return 0;
}
