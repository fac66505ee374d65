/* ss_report_plot.c — plots (being written). */
#include "ss_store.h"
