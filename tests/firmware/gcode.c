/* The subset of Marlin 1.1.9's serial protocol a print uses, with Marlin's message texts:
 * numbered, checksummed lines (N.. *..) answered with ok, or an error, `Resend:` and ok;
 * M104/M105/M109/M155 on the heaters (heaters.c), G1 E as step pulses at the feed rate, M82/M83,
 * G92 E, G4, T0/T1, M42 P11, M280 P0, M400, M110, M115, M112. */
#include "board.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <stdlib.h>
#include <string.h>

static int32_t last_n;             /* gcode_LastN */
static uint8_t tool;
static bool relative_e = false;    /* M83 */
static float e_mm[HOTENDS];        /* commanded E position per extruder */
static int32_t e_steps[HOTENDS];   /* steps issued: the position rounded, so pieces add up */
static uint8_t autoreport_s;
static uint32_t autoreport_ms, keepalive_ms;
static bool busy;                  /* a command blocks: keepalive lines go out */

static void ok(void) { serial_write("ok\n"); }

static void line_error(const char* what) {
    serial_write("Error:");
    serial_write(what);
    serial_write(", Last Line: ");
    serial_write_long(last_n);
    serial_write("\nResend: ");
    serial_write_long(last_n + 1);
    serial_write_char('\n');
    ok();
}

/* The value after `letter` in `args`, if the word is there. */
static bool word(const char* args, char letter, float* value) {
    for (const char* p = args; *p; ++p) {
        if (*p == letter && (p == args || p[-1] == ' ')) {
            *value = (float)strtod(p + 1, NULL);
            return true;
        }
    }
    return false;
}

static int32_t tenths(float c) { return (int32_t)(c * 10.0f + (c < 0 ? -0.5f : 0.5f)); }

static void temp_pair(const char* name, uint8_t h) {
    serial_write(name);
    serial_write_tenths(tenths(heater_temp(h)));
    serial_write(" /");
    serial_write_tenths(tenths(heater_target(h)));
}

/* " T:.. /.. T0:.. /.. T1:.. /.. @:0 @0:0 @1:0", as Marlin prints its heaters. */
static void heater_states(void) {
    temp_pair(" T:", tool);
    temp_pair(" T0:", 0);
    temp_pair(" T1:", 1);
    serial_write(" @:");
    serial_write_long(heater_power(tool));
    serial_write(" @0:");
    serial_write_long(heater_power(0));
    serial_write(" @1:");
    serial_write_long(heater_power(1));
}

void idle(void) {
    heaters_manage();
    const uint32_t now = millis();
    if (busy && now - keepalive_ms >= KEEPALIVE_MS) {
        keepalive_ms = now;
        serial_write("echo:busy: processing\n");
    }
    if (autoreport_s && now - autoreport_ms >= 1000u * autoreport_s) {
        autoreport_ms = now;
        heater_states();
        serial_write_char('\n');
    }
    /* Sleep until the next interrupt (the 1 kHz clock at the latest): the simulator skips the
     * cycles instead of running a busy loop. */
    set_sleep_mode(SLEEP_MODE_IDLE);
    cli();
    sleep_enable();
    sei();
    sleep_cpu();
    sleep_disable();
}

static void block_start(void) {
    busy = true;
    keepalive_ms = millis();
}

static void move_e(const char* args) {
    float e, f;
    if (!word(args, 'E', &e)) return;
    static float feed_mm_min = 300;
    if (word(args, 'F', &f) && f > 0) feed_mm_min = f;
    if (heater_temp(tool) < MIN_EXTRUDE_TEMP_C) {
        serial_write("echo: cold extrusion prevented\n");
        return;
    }
    e_mm[tool] = relative_e ? e_mm[tool] + e : e;
    const float exact = e_mm[tool] * STEPS_PER_MM;
    const int32_t target = (int32_t)(exact + (exact < 0 ? -0.5f : 0.5f));
    const int32_t steps = target - e_steps[tool];
    e_steps[tool] = target;
    block_start();
    while (!stepper_queue(tool, steps, feed_mm_min / 60.0f * STEPS_PER_MM)) idle();
    busy = false;
}

static void wait_moves(void) {
    block_start();
    while (!stepper_idle()) idle();
    busy = false;
}

static void dwell(const char* args) {
    float p = 0, s = 0;
    word(args, 'P', &p);
    if (word(args, 'S', &s)) p = s * 1000;
    wait_moves();
    block_start();
    const uint32_t start = millis();
    while (millis() - start < (uint32_t)p) idle();
    busy = false;
}

/* M109: wait until the hotend is within 1 degree of its target, reporting every second. */
static void wait_heater(uint8_t h) {
    uint32_t report = millis();
    for (;;) {
        idle();
        const float t = heater_temp(h), target = heater_target(h);
        if (target <= 0 || (t > target - 1 && t < target + 1)) break;
        if (millis() - report >= 1000) {
            report = millis();
            heater_states();
            serial_write(" W:?\n");
        }
    }
}

static uint8_t tool_of(const char* args) {
    float t;
    if (word(args, 'T', &t) && t >= 0 && t < HOTENDS) return (uint8_t)t;
    return tool;
}

static void m115(void) {
    serial_write("FIRMWARE_NAME:fibrecell-test-firmware (tests/firmware) SOURCE_CODE_URL:none "
                 "PROTOCOL_VERSION:1.0 MACHINE_TYPE:GT2560 EXTRUDER_COUNT:2 UUID:none\n"
                 "Cap:AUTOREPORT_TEMP:1\nCap:EMERGENCY_PARSER:0\nCap:THERMAL_PROTECTION:1\n");
}

static void execute(char* cmd) {
    while (*cmd == ' ') ++cmd;
    const char letter = *cmd;
    const long code = strtol(cmd + 1, NULL, 10);
    const char* args = cmd + 1;
    float v;
    if (letter == 'G' && (code == 0 || code == 1)) move_e(args);
    else if (letter == 'G' && code == 4) dwell(args);
    else if (letter == 'G' && code == 92) {
        if (word(args, 'E', &v)) {
            e_mm[tool] = v;
            const float exact = v * STEPS_PER_MM;
            e_steps[tool] = (int32_t)(exact + (exact < 0 ? -0.5f : 0.5f));
        }
    } else if (letter == 'M' && code == 82) relative_e = false;
    else if (letter == 'M' && code == 83) relative_e = true;
    else if (letter == 'M' && (code == 104 || code == 109)) {
        const uint8_t h = tool_of(args);
        if (word(args, 'S', &v)) heater_set_target(h, v);
        if (code == 109) wait_heater(h);
    } else if (letter == 'M' && code == 105) {
        serial_write("ok");
        heater_states();
        serial_write_char('\n');
        return; /* the report is the ok */
    } else if (letter == 'M' && code == 155) {
        autoreport_s = word(args, 'S', &v) ? (uint8_t)v : 0;
        autoreport_ms = millis();
    } else if (letter == 'M' && code == 400) wait_moves();
    else if (letter == 'M' && code == 42) {
        float pin = -1, s = 0;
        word(args, 'P', &pin);
        word(args, 'S', &s);
        if (pin == 11) {
            servo_detach();
            if (s > 0) PORTB |= _BV(PB5);
            else PORTB &= (uint8_t)~_BV(PB5);
        } else {
            serial_write("echo:Protected Pin\n");
        }
    } else if (letter == 'M' && code == 280) {
        if (word(args, 'S', &v)) servo_write((uint8_t)v);
    } else if (letter == 'M' && code == 115) m115();
    else if (letter == 'M' && code == 110) {
        if (word(args, 'N', &v)) last_n = (int32_t)v;
    } else if (letter == 'M' && code == 112) {
        heaters_off();
        serial_write("Error:Printer halted. kill() called!\n");
        cli();
        for (;;) {}
    } else if (letter == 'T' && (code == 0 || code == 1)) {
        tool = (uint8_t)code;
        serial_write("echo:Active Extruder: ");
        serial_write_long(tool);
        serial_write_char('\n');
    } else {
        serial_write("echo:Unknown command: \"");
        serial_write(cmd);
        serial_write("\"\n");
    }
    ok();
}

void gcode_line(char* line) {
    char* cmd = line;
    char* star = strchr(line, '*');
    if (*line == 'N') {
        char* end;
        const int32_t n = strtol(line + 1, &end, 10);
        cmd = end;
        const bool m110 = strstr(cmd, "M110") != NULL;
        if (n != last_n + 1 && !m110) {
            line_error("Line Number is not Last Line Number+1");
            return;
        }
        if (!star) {
            line_error("No Checksum with line number");
            return;
        }
        uint8_t sum = 0;
        for (const char* p = line; p < star; ++p) sum ^= (uint8_t)*p;
        if (strtol(star + 1, NULL, 10) != sum) {
            line_error("checksum mismatch");
            return;
        }
        *star = '\0';
        last_n = n; /* "N5 M110 N5" also sets it when M110 runs; "N5 M110" keeps the line's own */
    } else if (star) {
        line_error("No Line Number with checksum");
        return;
    }
    execute(cmd);
}
