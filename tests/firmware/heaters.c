#include "board.h"

#include <avr/io.h>
#include <math.h>

static float temp_c[HOTENDS];
static float target_c[HOTENDS];
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

/* Thermistor table 1 (EPCOS 100k, beta 4092) on a 4.7 kOhm pull-up to 5 V. */
static float thermistor_c(uint16_t adc) {
    if (adc >= 1023) return -20;    /* open sensor */
    if (adc == 0) return 999;       /* short */
    const float r = 4700.0f * adc / (1023.0f - adc);
    return 1.0f / (1.0f / 298.15f + logf(r / 100000.0f) / 4092.0f) - 273.15f;
}

static void heater_pin(uint8_t h, bool on) {
    const uint8_t bit = h == 0 ? _BV(PE4) : _BV(PE5);
    if (on) PORTE |= bit;
    else PORTE &= (uint8_t)~bit;
}

void heaters_init(void) {
    DDRE |= _BV(PE4) | _BV(PE5);
    heaters_off();
    for (uint8_t h = 0; h < HOTENDS; ++h) temp_c[h] = thermistor_c(adc_read(h));
}

void heaters_manage(void) {
    const uint32_t now = millis();
    if (now - last_ms < 100) return;
    last_ms = now;
    for (uint8_t h = 0; h < HOTENDS; ++h) {
        temp_c[h] = thermistor_c(adc_read(h));
        heater_pin(h, target_c[h] > 0 && temp_c[h] < target_c[h]);
    }
}

float heater_temp(uint8_t h) { return temp_c[h]; }
float heater_target(uint8_t h) { return target_c[h]; }
void heater_set_target(uint8_t h, float c) { target_c[h] = c; }

void heaters_off(void) {
    for (uint8_t h = 0; h < HOTENDS; ++h) {
        target_c[h] = 0;
        heater_pin(h, false);
    }
}
