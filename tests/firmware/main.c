/* fibrecell's GT2560 test firmware: enough of Marlin 1.1.9's behaviour on the real board's pins
 * to prove the board simulator (drivers/sim/avr) against known answers. Written here, for
 * ATmega2560 at 16 MHz; built with Debian's gcc-avr (tests/firmware/CMakeLists.txt). */
#include "board.h"

#include <avr/interrupt.h>
#include <avr/io.h>

int main(void) {
    clock_init();
    serial_init();
    heaters_init();
    stepper_init();
    servo_init();
    sei();
    serial_write("start\necho:fibrecell test firmware\n");

    char line[MAX_LINE];
    uint8_t len = 0;
    bool comment = false, overflow = false;
    for (;;) {
        const int c = serial_read();
        if (c < 0) {
            idle();
            continue;
        }
        if (c == '\n' || c == '\r') {
            if (len > 0 && !overflow) {
                line[len] = '\0';
                gcode_line(line);
            }
            len = 0;
            comment = overflow = false;
        } else if (c == ';') {
            comment = true;
        } else if (!comment) {
            if (len < MAX_LINE - 1) line[len++] = (char)c;
            else overflow = true;
        }
    }
}
