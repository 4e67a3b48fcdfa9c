/* view.h — `fluidcast view`: an interactive SDL2 window on fluidcastd. */
#ifndef FC_VIEW_H
#define FC_VIEW_H

int fc_view_main(int argc, char **argv);

#endif
