// navfn-smt: included by Humble's layers; the oracle's layers subscribe to nothing through it.
#pragma once
