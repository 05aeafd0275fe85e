#include "board.h"

#include <avr/interrupt.h>
#include <avr/io.h>
#include <util/atomic.h>

/* One extruder move: |steps| pulses at a fixed rate (no acceleration: the board simulator's
 * tests measure the feed against the rate). */
typedef struct {
    uint8_t extruder;
    bool forward;
    uint32_t steps;
    uint16_t ocr; /* timer 1 ticks (2 MHz) per step, minus one */
} Move;

#define QUEUE 5 /* four moves and the free slot that tells full from empty */
static volatile Move queue[QUEUE];
static volatile uint8_t q_head, q_tail; /* head: next to run; tail: next free */
static volatile uint32_t left;          /* steps left of the running move, at queue[q_head] */
static volatile bool running;

static void set_dir(uint8_t e, bool forward) {
    const uint8_t bit = e == 0 ? _BV(PL4) : _BV(PL2);
    if (forward != INVERT_E_DIR) PORTL |= bit;
    else PORTL &= (uint8_t)~bit;
}

static void enable(uint8_t e) {
    if (e == 0) PORTG &= (uint8_t)~_BV(PG0);
    else PORTL &= (uint8_t)~_BV(PL1);
}

/* Starts the move at the head of the queue; stops the timer when there is none. */
static void start_next(void) {
    if (q_head == q_tail) {
        running = false;
        TIMSK1 = 0;
        TCCR1B = _BV(WGM12);  /* clock off while idle: a running timer costs the simulator */
        return;
    }
    const volatile Move* m = &queue[q_head];
    enable(m->extruder);
    set_dir(m->extruder, m->forward);
    left = m->steps;
    OCR1A = m->ocr;
    TCNT1 = 0;
    running = true;
    TIMSK1 = _BV(OCIE1A);
    TCCR1B = _BV(WGM12) | _BV(CS11); /* CTC, 16 MHz / 8 = 2 MHz */
}

ISR(TIMER1_COMPA_vect) {
    const uint8_t bit = queue[q_head].extruder == 0 ? _BV(PL6) : _BV(PL0);
    PORTL |= bit;
    __asm__ __volatile__("nop\n\tnop\n\tnop\n\tnop");
    PORTL &= (uint8_t)~bit;
    if (--left == 0) {
        q_head = (uint8_t)((q_head + 1) % QUEUE);
        start_next();
    }
}

void stepper_init(void) {
    DDRL |= _BV(PL6) | _BV(PL4) | _BV(PL0) | _BV(PL2) | _BV(PL1);
    DDRG |= _BV(PG0);
    PORTG |= _BV(PG0); /* disabled until the first move */
    PORTL |= _BV(PL1);
    TCCR1A = 0;
    TCCR1B = _BV(WGM12); /* CTC; the clock runs only while a move does */
}

bool stepper_queue(uint8_t extruder, int32_t steps, float steps_per_s) {
    if (steps == 0) return true;
    const uint8_t next = (uint8_t)((q_tail + 1) % QUEUE);
    if (next == q_head) return false;
    float ticks = 2000000.0f / steps_per_s - 1.0f;
    if (ticks < 49) ticks = 49;       /* 40 k steps/s at most */
    if (ticks > 65535) ticks = 65535; /* about 30.5 steps/s at least */
    volatile Move* m = &queue[q_tail];
    m->extruder = extruder;
    m->forward = steps > 0;
    m->steps = (uint32_t)(steps > 0 ? steps : -steps);
    m->ocr = (uint16_t)ticks;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        q_tail = next;
        if (!running) start_next();
    }
    return true;
}

bool stepper_idle(void) {
    bool idle;
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { idle = !running && q_head == q_tail; }
    return idle;
}
