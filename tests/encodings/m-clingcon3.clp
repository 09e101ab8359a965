% m-clingcon3.clp -- a constraint program in clingcon 3's language (written for the tests).
#include <csp>.
#include "m-single.lp".
$domain(0..10).
robot(R) $<= 10 :- robot(R).
