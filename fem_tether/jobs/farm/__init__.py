"""Farm jobs: Fagiano et al.'s KE-farm (eqs. 23–24) solved, rated and flown on the FE line."""
