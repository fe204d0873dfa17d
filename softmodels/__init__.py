"""softmodels: dynamic soft-robot models of thesis chapter 4 (issue 15)."""
