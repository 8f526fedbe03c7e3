#include "support/check.h"
int main(void) { return t_status(); }
