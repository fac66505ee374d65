/* ss_report_table.c — table writers (being written). */
#include "ss_store.h"
