/* tinted_look.h — the look of the tests that find the fluid in a picture by
 * its colour (bluer than the grey floor and sky): water that absorbs strongly
 * enough to be plainly blue in a small ball, given as an option so that the
 * default look, whose shallow water is nearly clear, may change without them. */
#ifndef FC_TEST_TINTED_LOOK_H
#define FC_TEST_TINTED_LOOK_H

/* --absorption's value: per particle radius of thickness, R,G,B. */
#define TINTED_LOOK_ABSORPTION "0.2,0.07,0.035"
/* The same as an initializer of fc_settings.absorption. */
#define TINTED_LOOK_ABSORPTION_RGB {0.2f, 0.07f, 0.035f}

#endif
