#include "board.h"

#include <avr/interrupt.h>
#include <avr/io.h>

static volatile uint8_t rx[RX_BUFFER_SIZE];
static volatile uint8_t rx_head, rx_tail;

/* A byte that finds the ring full is dropped, as Marlin's RX interrupt does. */
ISR(USART0_RX_vect) {
    const uint8_t c = UDR0;
    const uint8_t next = (uint8_t)((rx_head + 1) % RX_BUFFER_SIZE);
    if (next != rx_tail) {
        rx[rx_head] = c;
        rx_head = next;
    }
}

void serial_init(void) {
    /* The Arduino core's init() clears UCSR0B before the sketch opens the port; simavr 1.6 then
     * never sets UDRE again by itself, which the board simulator has to work around. Doing the
     * same here proves that it does. */
    UCSR0B = 0;
    UCSR0A = _BV(U2X0);
    UBRR0H = 0;
    UBRR0L = 7; /* 16 MHz / (8 * (7 + 1)) = 250000 baud */
    UCSR0C = _BV(UCSZ01) | _BV(UCSZ00);
    UCSR0B = _BV(RXEN0) | _BV(TXEN0) | _BV(RXCIE0);
}

int serial_read(void) {
    if (rx_head == rx_tail) return -1;
    const uint8_t c = rx[rx_tail];
    rx_tail = (uint8_t)((rx_tail + 1) % RX_BUFFER_SIZE);
    return c;
}

void serial_write_char(char c) {
    while (!(UCSR0A & _BV(UDRE0))) {}
    UDR0 = (uint8_t)c;
}

void serial_write(const char* s) {
    while (*s) serial_write_char(*s++);
}

void serial_write_long(int32_t v) {
    char buf[12];
    uint8_t n = 0;
    uint32_t u = v < 0 ? (uint32_t)(-v) : (uint32_t)v;
    do {
        buf[n++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0) serial_write_char('-');
    while (n) serial_write_char(buf[--n]);
}

void serial_write_tenths(int32_t tenths) {
    if (tenths < 0) {
        serial_write_char('-');
        tenths = -tenths;
    }
    serial_write_long(tenths / 10);
    serial_write_char('.');
    serial_write_char((char)('0' + tenths % 10));
}
