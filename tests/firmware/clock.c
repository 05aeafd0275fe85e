#include "board.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <util/atomic.h>

static volatile uint32_t ms;

ISR(TIMER0_COMPA_vect) { ++ms; }

void clock_init(void) {
    TCCR0A = _BV(WGM01);             /* CTC */
    TCCR0B = _BV(CS01) | _BV(CS00);  /* 16 MHz / 64 = 250 kHz */
    OCR0A = 249;                     /* 1 kHz */
    TIMSK0 = _BV(OCIE0A);
}

uint32_t millis(void) {
    uint32_t v;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { v = ms; }
    return v;
}
