/** A run that cannot go on: the message says why. */
export class HarnessError extends Error {}
