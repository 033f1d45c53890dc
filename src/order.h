/* order.h: the solving order of a step's rows: under gravity, bottom-up by the height of
 * their contact points along it (written with each row, resolve.h), so that Gauss-Seidel
 * carries support up a stack within a sweep and the shock sweeps (solver.h) meet a stack
 * from the ground up; rows of equal height keep their staging order.  The heights become
 * 16-bit keys over the step's span of heights; the last step's order is repaired when it
 * held as many rows (a pile at rest keeps its rows and nearly their order), else the keys
 * are sorted afresh by a radix sort. */
#ifndef RG_ORDER_H
#define RG_ORDER_H

#include <stdint.h>

#include "solver.h"

/* rows->ord[0, nc): the solving order of rows [0, nc) (with down; without gravity, the
 * staging order); rows->key, tkey and tord are its scratch, rows->nord its hint. */
void order_rows(solver_rows *rows, int32_t nc, int down);

/* The order of n rows by (key, row) -- what the stable radix sort of the solving order gives
 * -- from the order held in ord, when that is a permutation of [0, n) close to it (the last
 * step's, in a pile that moved little): an insertion sort, given up (returning 0, ord then
 * scrambled) past some 4n moves or on finding ord is no permutation.  Whatever ord held,
 * success means ord is the one order of distinct rows by (key, row): the sort's result. */
int order_resort(const uint16_t *key, int32_t *ord, int32_t n);

#endif
