/* The EPCOS 100k NTC thermistor of hotends (B57560G104F, Marlin's thermistor 1), as resistance
 * against temperature: the board model turns a hotend's temperature into the thermistor's voltage
 * with it, and the test firmware (tests/firmware) reads the voltage back with it, as Marlin reads
 * it with its table 1. Plain C, so that both can include it.
 *
 * The rows are Marlin 1.1.9's table 1 (the part on a 4.7 kOhm pull-up, a 10-bit ADC count every
 * 5 C) with each count n turned back into ohms, R = 4.7 kOhm n / (1024 - n); they agree with the
 * EPCOS datasheet's 100 kOhm at 25 C, 1641.9 Ohm at 150 C and 226.15 Ohm at 250 C within 2.4%
 * (1.3 C). The beta formula (B = 4092 K) reads 5 C high at 200 C and 10 C high at 250 C against
 * them, which is why a model built on it made stock Marlin stall below its target
 * (docs/board-simulator.md). Between rows, ln R is linear in 1/T, the beta form. */
#ifndef FIBRECELL_EPCOS_100K_H
#define FIBRECELL_EPCOS_100K_H

#define EPCOS_100K_FIRST_C 0
#define EPCOS_100K_STEP_C 5
#define EPCOS_100K_ROWS 61 /* 0, 5, ..., 300 C */
#define EPCOS_100K_PULLUP_OHM 4700.0

/* [ohm] at EPCOS_100K_FIRST_C + i EPCOS_100K_STEP_C */
static const float epcos_100k_ohm[EPCOS_100K_ROWS] = {
    2.961e+05f, 2.359e+05f, 1.878e+05f, 1.506e+05f, 1.187e+05f, 9.77e+04f, 7.828e+04f,
    6.405e+04f, 5.192e+04f, 4.248e+04f, 3.508e+04f, 2.896e+04f, 2.412e+04f, 2.011e+04f,
    1.688e+04f, 1.425e+04f, 1.207e+04f, 1.025e+04f, 8706.0f,    7454.0f,    6415.0f,
    5518.0f,    4774.0f,    4147.0f,    3612.0f,    3151.0f,    2762.0f,    2420.0f,
    2136.0f,    1884.0f,    1666.0f,    1478.0f,    1316.0f,    1176.0f,    1050.0f,
    942.2f,     844.7f,     762.9f,     689.5f,     623.9f,     559.9f,     508.7f,
    463.9f,     420.0f,     387.5f,     350.2f,     323.8f,     297.7f,     271.9f,
    251.4f,     231.1f,     211.0f,     196.0f,     181.1f,     166.3f,     156.5f,
    146.7f,     132.1f,     127.3f,     117.6f,     108.0f};

#endif
