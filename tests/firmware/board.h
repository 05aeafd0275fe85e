/* The GT2560 Rev A pins and clocks the test firmware drives (the same pins stock Marlin 1.1.9
 * uses on this board: ../shared/hil/marlin-1.1.9-gt2560/README.md), and the small interfaces
 * between its files. */
#ifndef TESTFW_BOARD_H
#define TESTFW_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#define STEPS_PER_MM 105      /* both extruders, as the Marlin build */
#define HOTENDS 2
#define MIN_EXTRUDE_TEMP_C 170 /* PREVENT_COLD_EXTRUSION */
#define RX_BUFFER_SIZE 128     /* bytes; more are lost, as in Marlin */
#define MAX_LINE 96
#define KEEPALIVE_MS 2000      /* HOST_KEEPALIVE_FEATURE's interval */

/* Build options (tests/firmware/CMakeLists.txt builds both ways where it matters):
 * INVERT_E_DIR  1: the E direction pins are low for forward, as the Geeetech GT2560 example
 *               configuration's INVERT_E0_DIR / INVERT_E1_DIR true
 * HEATER_PID    1: Marlin's PID with the example's gains and PID_FUNCTIONAL_RANGE 10; 0: bang-bang
 * WATCH_TEMP_PERIOD_S, WATCH_TEMP_INCREASE_C: Marlin's heating watchdog (stock 20 s, 2 C) */
#ifndef INVERT_E_DIR
#define INVERT_E_DIR 0
#endif
#ifndef HEATER_PID
#define HEATER_PID 0
#endif
#ifndef WATCH_TEMP_PERIOD_S
#define WATCH_TEMP_PERIOD_S 20
#endif
#ifndef WATCH_TEMP_INCREASE_C
#define WATCH_TEMP_INCREASE_C 2
#endif

/* clock.c: milliseconds since reset (timer 0). */
void clock_init(void);
uint32_t millis(void);

/* serial.c: UART0 at 250000 baud, received bytes in a ring filled by the RX interrupt. */
void serial_init(void);
int serial_read(void);          /* -1 when nothing is waiting */
void serial_write(const char* s);
void serial_write_char(char c);
void serial_write_long(int32_t v);
void serial_write_tenths(int32_t tenths); /* 215 -> "21.5" */

/* heaters.c: thermistors on ADC8/ADC9, heaters on PE4/PE5 (bang-bang or PID, soft PWM), the
 * heating watchdog. */
void heaters_init(void);
void heaters_manage(void);      /* reads, controls and watches every sample; the PWM every call */
float heater_temp(uint8_t h);
float heater_target(uint8_t h);
uint8_t heater_power(uint8_t h); /* 0..255, Marlin's @ figure */
void heater_set_target(uint8_t h, float c);
void heaters_off(void);

/* stepper.c: E0 and E1 step pulses from timer 1, a queue of four moves like Marlin's blocks. */
void stepper_init(void);
bool stepper_queue(uint8_t extruder, int32_t steps, float steps_per_s); /* false: queue full */
bool stepper_idle(void);

/* servo.c: the servo pulse on D11 (PB5) from timer 3; M42 P11 drives the same pin directly. */
void servo_init(void);
void servo_write(uint8_t angle);
void servo_detach(void);

/* gcode.c */
void gcode_line(char* line);
void idle(void);                /* what runs while a command waits */

#endif
