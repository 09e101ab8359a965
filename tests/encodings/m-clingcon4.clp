% m-clingcon4.clp -- m-clingcon.lp as clingcon 4 programs began (written for the tests):
% with '#include <csp>.', which clingcon 5 no longer has.
#include <csp>.
#include "m-clingcon.lp".
