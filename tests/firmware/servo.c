#include "board.h"

#include <avr/interrupt.h>
#include <avr/io.h>

/* A 50 Hz pulse of 544..2400 us for 0..180 degrees (the Arduino Servo library's range). */
static volatile uint16_t high_ticks; /* timer 3 ticks at 2 MHz */
static volatile bool high;

ISR(TIMER3_COMPA_vect) {
    if (!high) {
        PORTB |= _BV(PB5);
        OCR3A = high_ticks;
    } else {
        PORTB &= (uint8_t)~_BV(PB5);
        OCR3A = (uint16_t)(40000u - high_ticks);
    }
    high = !high;
}

void servo_init(void) {
    DDRB |= _BV(PB5);
    TCCR3A = 0;
    TCCR3B = _BV(WGM32); /* CTC; the clock runs only while the servo is driven */
}

void servo_write(uint8_t angle) {
    if (angle > 180) angle = 180;
    high_ticks = (uint16_t)(2u * (544u + (uint32_t)(2400u - 544u) * angle / 180u));
    if (!(TIMSK3 & _BV(OCIE3A))) {
        high = false;
        OCR3A = 100;
        TCNT3 = 0;
        TIMSK3 = _BV(OCIE3A);
        TCCR3B = _BV(WGM32) | _BV(CS31); /* 2 MHz */
    }
}

void servo_detach(void) {
    TIMSK3 = 0;
    TCCR3B = _BV(WGM32);
    PORTB &= (uint8_t)~_BV(PB5);
}
