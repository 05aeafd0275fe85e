#include "board.h"

#include "drivers/sim/avr/epcos_100k.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <math.h>

static float temp_c[HOTENDS];
static float target_c[HOTENDS];
static uint8_t power[HOTENDS];     /* 0..255 of full power, as Marlin's soft PWM */
static uint32_t last_ms;

/* The 10-bit reading of ADC8 + h against AVCC. */
static uint16_t adc_read(uint8_t h) {
    ADMUX = _BV(REFS0);             /* AVCC reference, MUX4:0 = 0 */
    ADCSRB = _BV(MUX5);             /* with MUX5: ADC8 */
    ADMUX |= h;                     /* ADC9 for h = 1 */
    ADCSRA = _BV(ADEN) | _BV(ADSC) | _BV(ADPS2) | _BV(ADPS1) | _BV(ADPS0);
    while (ADCSRA & _BV(ADSC)) {}
    return ADC;
}

/* The EPCOS 100k on a 4.7 kOhm pull-up to 5 V, read back through its resistance table. */
static float thermistor_c(uint16_t adc) {
    if (adc >= 1023) return -20;    /* open sensor */
    if (adc == 0) return 999;       /* short */
    const float ln_r = logf(EPCOS_100K_PULLUP_OHM * adc / (1024.0f - adc));
    uint8_t i = 0;
    while (i < EPCOS_100K_ROWS - 2 && logf(epcos_100k_ohm[i + 1]) > ln_r) ++i;
    const float t0 = EPCOS_100K_FIRST_C + i * EPCOS_100K_STEP_C + 273.15f;
    const float t1 = t0 + EPCOS_100K_STEP_C;
    const float ln0 = logf(epcos_100k_ohm[i]), ln1 = logf(epcos_100k_ohm[i + 1]);
    const float inv_t = 1 / t0 + (ln_r - ln0) / (ln1 - ln0) * (1 / t1 - 1 / t0);
    return 1 / inv_t - 273.15f;
}

static void heater_pin(uint8_t h, bool on) {
    const uint8_t bit = h == 0 ? _BV(PE4) : _BV(PE5);
    if (on) PORTE |= bit;
    else PORTE &= (uint8_t)~bit;
}

#if HEATER_PID
/* Marlin's PID as the GT2560 example configures it: full power until PID_FUNCTIONAL_RANGE below
 * the target, off above it, and within it P + I - D on the reading every 164 ms, the integral
 * kept within full power and the derivative filtered (Marlin's PID_K1 0.95). */
#define PID_KP 12.33f
#define PID_KI 0.51f                  /* per second */
#define PID_KD 74.50f                 /* seconds */
#define PID_FUNCTIONAL_RANGE 10
/* About Marlin 1.1.9's PID_dT: 16 x 10 ADC samples at 976.6 Hz. */
#define SAMPLE_MS 164
#define PID_DT (SAMPLE_MS / 1000.0f)
static float i_state[HOTENDS], d_term[HOTENDS], last_c[HOTENDS];
static bool pid_reset[HOTENDS];

static uint8_t control(uint8_t h) {
    const float error = target_c[h] - temp_c[h];
    d_term[h] = 0.95f * d_term[h] + 0.05f * (PID_KD / PID_DT) * (last_c[h] - temp_c[h]);
    last_c[h] = temp_c[h];
    if (target_c[h] <= 0 || error < -PID_FUNCTIONAL_RANGE) {
        pid_reset[h] = true;
        return 0;
    }
    if (error > PID_FUNCTIONAL_RANGE) {
        pid_reset[h] = true;
        return 255;
    }
    if (pid_reset[h]) {
        i_state[h] = 0;
        pid_reset[h] = false;
    }
    i_state[h] = fminf(fmaxf(i_state[h] + error, 0), 255 / (PID_KI * PID_DT));
    const float out = PID_KP * error + PID_KI * PID_DT * i_state[h] - d_term[h];
    return (uint8_t)fminf(fmaxf(out, 0), 255);
}
#else
#define SAMPLE_MS 100
/* Bang-bang: on below the target. Quick to settle on any hotend model, which the tests that
 * shrink the heat capacity to save time need. */
static uint8_t control(uint8_t h) { return target_c[h] > 0 && temp_c[h] < target_c[h] ? 255 : 0; }
#endif

/* Marlin's heating watchdog (WATCH_TEMP_PERIOD / WATCH_TEMP_INCREASE): while a hotend heats
 * towards a new target from more than the increase plus TEMP_HYSTERESIS (3) and 1 below it, each
 * period must raise it by the increase, else the printer halts. */
static float watch_c[HOTENDS];
static uint32_t watch_until_ms[HOTENDS]; /* 0: not watching */

static void start_watching(uint8_t h) {
    watch_until_ms[h] = 0;
    if (target_c[h] > 0 && temp_c[h] < target_c[h] - (WATCH_TEMP_INCREASE_C + 3 + 1)) {
        watch_c[h] = temp_c[h] + WATCH_TEMP_INCREASE_C;
        watch_until_ms[h] = millis() + 1000ul * WATCH_TEMP_PERIOD_S;
        if (watch_until_ms[h] == 0) watch_until_ms[h] = 1;
    }
}

/* As Marlin's kill(): heaters off, the reason, and nothing more until a reset. */
static void halt_heating_failed(uint8_t h) {
    heaters_off();
    serial_write("Error:Heating failed, system stopped! Heater_ID: ");
    serial_write_long(h);
    serial_write("\nError:Printer halted. kill() called!\n");
    cli();
    for (;;) {}
}

void heaters_init(void) {
    DDRE |= _BV(PE4) | _BV(PE5);
    heaters_off();
    for (uint8_t h = 0; h < HOTENDS; ++h) {
        temp_c[h] = thermistor_c(adc_read(h));
#if HEATER_PID
        last_c[h] = temp_c[h];
#endif
    }
}

/* Every sample: read both sensors, run the control and the watchdog. Every call: the heater pins
 * from their power, a soft PWM of 128 ms (the caller runs at least every millisecond). */
void heaters_manage(void) {
    const uint32_t now = millis();
    if (now - last_ms >= SAMPLE_MS) {
        last_ms = now;
        for (uint8_t h = 0; h < HOTENDS; ++h) {
            temp_c[h] = thermistor_c(adc_read(h));
            power[h] = control(h);
            if (watch_until_ms[h] && (int32_t)(now - watch_until_ms[h]) >= 0) {
                if (temp_c[h] < watch_c[h]) halt_heating_failed(h);
                start_watching(h);
            }
        }
    }
    const uint8_t phase = (uint8_t)((now & 127u) << 1); /* 0, 2, ..., 254 */
    for (uint8_t h = 0; h < HOTENDS; ++h) heater_pin(h, power[h] > phase);
}

float heater_temp(uint8_t h) { return temp_c[h]; }
float heater_target(uint8_t h) { return target_c[h]; }
uint8_t heater_power(uint8_t h) { return power[h]; }

void heater_set_target(uint8_t h, float c) {
    target_c[h] = c;
    start_watching(h);
}

void heaters_off(void) {
    for (uint8_t h = 0; h < HOTENDS; ++h) {
        target_c[h] = 0;
        power[h] = 0;
        watch_until_ms[h] = 0;
        heater_pin(h, false);
    }
}
