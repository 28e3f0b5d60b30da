"""Why a Nav2 NavFn plan fails or looks wrong, and what fixes it."""
